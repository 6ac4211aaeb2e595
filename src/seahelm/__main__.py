"""``python -m seahelm``: the ``seahelm`` command (same options, output and exit codes)."""

from seahelm.cli import main

if __name__ == "__main__":
    main()

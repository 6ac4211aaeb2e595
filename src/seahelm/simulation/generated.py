"""Generated modules for the engine: :mod:`seahelm._codegen`, re-exported.

The kernel cache directory, the code fingerprint that names a generated module, its import and
its in-memory run for the pure-Python closed loop (``simulate(..., jit=False)``:
:func:`exec_generated` writes nothing to the cache directory and gives debuggers and tracebacks
its source) live under every layer in :mod:`seahelm._codegen` (the guided controllers generate
code too and import no simulation module); the engine imports them from here.
"""

from __future__ import annotations

from .._codegen import code_fingerprint, exec_generated, import_generated, kernel_cache_dir

__all__ = ["kernel_cache_dir", "code_fingerprint", "import_generated", "exec_generated"]

"""One name for a result's report (issue 44, item 7): ``seahelm run --report`` and ``seahelm
demo`` wrote ``report.html`` beside ``result.nc`` and ``seahelm report result.nc`` the same page
as ``result.html``. Now every command names it ``report.html``; a name given with ``-o`` (the
old ``result.html`` too) is written as given."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from seahelm.cli.main import app

runner = CliRunner()


def _json(args):
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_run_and_report_give_a_result_s_report_one_name(tmp_path):
    out = tmp_path / "out"
    assert runner.invoke(app, ["demo", "--out", str(out)]).exit_code == 0
    assert (out / "report.html").is_file()
    first = (out / "report.html").stat().st_mtime_ns
    got = _json(["report", str(out / "result.nc")])
    # the page `demo` wrote, written again under its own name (a report over a report)
    assert got["report"] == str(out / "report.html")
    assert (out / "report.html").stat().st_mtime_ns >= first
    assert sorted(p.name for p in out.iterdir()) == ["overview.png", "report.html", "result.nc"]


def test_the_old_name_is_written_when_given(tmp_path):
    out = tmp_path / "out"
    assert runner.invoke(app, ["demo", "--out", str(out)]).exit_code == 0
    got = _json(["report", str(out / "result.nc"), "-o", str(out / "result.html")])
    assert got["report"] == str(out / "result.html") and (out / "result.html").is_file()


def test_the_help_names_the_default():
    res = runner.invoke(app, ["report", "--help"], env={"COLUMNS": "80"})
    text = " ".join(res.stdout.replace("│", " ").split())
    assert "default: report.html beside RESULT" in text, text


def test_a_report_of_other_results_is_not_replaced_without_force(tmp_path):
    """``seahelm report b.nc`` beside ``a.nc``'s report.html replaced it silently (the policy
    took any seahelm page for the command's own output); the page now names the files it is
    the report of, and a report of other files needs ``--force``."""
    out = tmp_path / "out"
    assert runner.invoke(app, ["demo", "--out", str(out)]).exit_code == 0
    (out / "result.nc").rename(out / "a.nc")
    import shutil

    shutil.copy(out / "a.nc", out / "b.nc")
    (out / "report.html").unlink()
    assert _json(["report", str(out / "a.nc")])["report"] == str(out / "report.html")
    page = (out / "report.html").read_bytes()
    assert b'<meta name="seahelm-report-of" content="a.nc">' in page
    res = runner.invoke(app, ["report", str(out / "b.nc")])
    assert res.exit_code == 2
    assert "a seahelm report of other files, not the report of b.nc" in res.output
    assert "pass --force" in res.output
    assert (out / "report.html").read_bytes() == page  # untouched
    # its own report again, and the other one with --force
    assert _json(["report", str(out / "a.nc")])["report"] == str(out / "report.html")
    assert _json(["report", str(out / "b.nc"), "--force"])["report"] == str(out / "report.html")
    assert b'content="b.nc"' in (out / "report.html").read_bytes()

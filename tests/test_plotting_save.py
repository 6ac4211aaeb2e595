"""save_figure: the format follows the suffix, bad suffixes are refused, nothing half-written."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from seahelm.errors import ParameterError  # noqa: E402
from seahelm.plotting.save import save_figure  # noqa: E402


def _figure():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    return fig


@pytest.mark.parametrize(("name", "magic"), [("f.png", b"\x89PNG"), ("f.pdf", b"%PDF"),
                                             ("f.SVG", b"<?xml")])
def test_the_suffix_chooses_the_format(tmp_path, name, magic):
    fig = _figure()
    path = save_figure(fig, tmp_path / name)
    assert path.read_bytes().startswith(magic)
    assert not plt.fignum_exists(fig.number)  # closed after


def test_no_suffix_writes_png_and_says_where(tmp_path):
    path = save_figure(_figure(), tmp_path / "overview")
    assert path.name == "overview.png" and path.read_bytes().startswith(b"\x89PNG")


def test_unsupported_suffix_is_refused_and_nothing_is_left(tmp_path):
    fig = _figure()
    with pytest.raises(ParameterError, match=r"'\.docx'.*supported: .*\.pdf.*\.png"):
        save_figure(fig, tmp_path / "f.docx")
    assert list(tmp_path.iterdir()) == []
    assert not plt.fignum_exists(fig.number)


def test_an_axes_saves_its_figure_and_close_false_keeps_it_open(tmp_path):
    fig = _figure()
    save_figure(fig.axes[0], tmp_path / "a.png", close=False)
    assert plt.fignum_exists(fig.number)
    plt.close(fig)

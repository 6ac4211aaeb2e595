"""Tables that fit the terminal, or a pipe's 80 columns, without breaking what they say.

rich shrinks a table that is wider than the console by wrapping and then truncating its
columns, which splits numbers across lines ("-1.812" / "e-05") and cuts words ("crite…").
:class:`FitTables`, a render hook on the CLI's consoles, gives every table printed there
column widths of its own when it does not fit as it is:

- a numeric column (every cell a number, or blank, "-", "—", "nan") keeps its full width and
  never wraps;
- text columns (and headers) wrap at spaces only, never below their longest word, sharing
  the width that is left;
- when that does not fit, with light rules, no edges and two spaces between columns;
- when only the first column (a label) is in the way, each row's label on a line of its
  own, its other cells aligned under the headers below it;
- when even that does not fit, the table is printed as key/value lines: each row's first
  cell as a heading, then ``header: value`` for its other cells.

A table that fits is printed as it was built.
"""

from __future__ import annotations

import re
from typing import Any

from rich import box
from rich.console import Console, ConsoleRenderable, Group, RenderHook
from rich.measure import Measurement
from rich.table import Table
from rich.text import Text

_NUMBER = re.compile(r"[+-−]?(\d[\d,_]*(\.\d*)?|\.\d+)([eE][+-]?\d+)?%?")
_BLANKS = frozenset({"", "-", "—", "–", "nan", "NaN", "inf", "-inf", "n/a"})


def _plain(renderable: Any) -> str:
    if isinstance(renderable, Text):
        return renderable.plain
    if isinstance(renderable, str):
        try:
            return Text.from_markup(renderable).plain
        except Exception:  # noqa: BLE001 - not markup: the text itself
            return renderable
    return ""


def is_numeric(cells: list[Any]) -> bool:
    """Whether a column's cells are all numbers or blanks, at least one a number."""
    texts = [_plain(c).strip() for c in cells]
    numbers = [t for t in texts if t not in _BLANKS]
    return bool(numbers) and all(_NUMBER.fullmatch(t) for t in numbers)


def _measure(console: Console, options: Any, renderable: Any) -> Measurement:
    if renderable is None or renderable == "":
        return Measurement(0, 0)
    return Measurement.get(console, options, renderable)


def _overhead(table: Table, console: Console, options: Any) -> int:
    """Columns a table takes besides its cells' text: padding, rules and edges."""
    saved = [c.width for c in table.columns]
    for column in table.columns:
        column.width = 1
    overhead = _measure(console, options, table).maximum - len(table.columns)
    for column, w in zip(table.columns, saved):
        column.width = w
    return overhead


def fit_table(table: Table, console: Console, width: int | None = None) -> ConsoleRenderable:
    """``table`` with column widths that fit ``width`` columns, or its key/value lines.

    Parameters
    ----------
    table : rich.table.Table
    console : rich.console.Console
        The console it is printed on (for measuring).
    width : int, optional
        Columns available (default: the console's width).

    Returns
    -------
    rich.console.ConsoleRenderable
        The table itself (its columns' widths set if it had to shrink), or a group of lines.
    """
    width = console.width if width is None else width
    columns = table.columns
    if not columns or table.row_count == 0 or table.width is not None:
        return table
    wide = console.options.update_width(10**4)
    if _measure(console, wide, table).maximum <= width:
        return table  # fits as built
    low, high, numeric = [], [], []
    for column in columns:
        cells = list(column.cells)
        cell_m = [_measure(console, wide, c) for c in cells]
        head = _measure(console, wide, column.header)
        number = is_numeric(cells)
        most = max([m.maximum for m in cell_m] + [head.maximum])
        least = max([m.maximum if number else m.minimum for m in cell_m] + [head.minimum])
        if column.no_wrap or column.width is not None:
            least = most = column.width or most
        least = max(least, column.min_width or 0)
        low.append(least)
        high.append(max(most, least))
        numeric.append(number)
    available = width - _overhead(table, console, wide)
    if sum(low) > available and table.box not in (None, box.SIMPLE_HEAD):
        table.box, table.show_edge, table.pad_edge = box.SIMPLE_HEAD, False, False
        table.padding = (0, 1, 0, 0)
        available = width - _overhead(table, console, wide)  # (lighter rules, no edges)
    if sum(low) > available:
        rest = width - 2 * (len(columns) - 1)  # (label_above: two spaces after each column)
        if len(columns) > 2 and not numeric[0] and sum(low[1:]) <= rest:
            return label_above(table, _share(low[1:], high[1:], rest), numeric[1:])
        return key_value_lines(table)
    widths = _share(low, high, available)
    for column, w in zip(columns, widths):
        # (a numeric column is as wide as its widest number, so no number wraps; no_wrap
        # would crop its header instead of wrapping it: "final heading [deg]" as "final h")
        column.width = w
        column.overflow = "fold"
    return table


def _share(low: list[int], high: list[int], available: int) -> list[int]:
    """Widths from the least each column needs, the rest given where most is wanted."""
    widths = list(low)
    for _ in range(available - sum(low)):
        deficit = [h - w for h, w in zip(high, widths)]
        i = max(range(len(widths)), key=deficit.__getitem__)
        if deficit[i] <= 0:
            break
        widths[i] += 1
    return widths


def label_above(table: Table, widths: list[int], numeric: list[bool]) -> Group:
    """A table whose first column is too wide to sit beside the others: each row's first cell
    on a line of its own, the row's other cells aligned under the headers below it.

    Parameters
    ----------
    table : rich.table.Table
    widths : list of int
        Widths of the other columns.
    numeric : list of bool
        Which of the other columns hold numbers (they never wrap).

    Returns
    -------
    rich.console.Group
    """
    columns = table.columns[1:]
    first = list(table.columns[0].cells)

    def piece(show_header: bool) -> Table:
        t = Table(box=None, show_header=show_header, show_edge=False, pad_edge=False,
                  padding=(0, 2, 0, 0), header_style=table.header_style)
        for column, w, number in zip(columns, widths, numeric):
            t.add_column(column.header, justify=column.justify, width=w,
                         no_wrap=number or column.no_wrap, overflow="fold")
        return t

    parts: list[Any] = []
    if table.title:
        parts.append(table.title if isinstance(table.title, Text) else Text.from_markup(
            str(table.title), style="italic"))
    parts.append(piece(True))
    cells = [list(c.cells) for c in columns]
    for row, label in enumerate(first):
        parts.append(Text.from_markup(label, style="bold") if isinstance(label, str)
                     else label)
        one = piece(False)
        one.add_row(*(c[row] for c in cells))
        parts.append(one)
    if table.caption:
        parts.append(Text.from_markup(str(table.caption), style="dim"))
    return Group(*parts)


def key_value_lines(table: Table) -> Group:
    """A table as lines: its title, then per row the first cell and ``header: value`` lines.

    Parameters
    ----------
    table : rich.table.Table

    Returns
    -------
    rich.console.Group
    """
    columns = table.columns
    headers = [_plain(c.header) for c in columns]
    cells = [list(c.cells) for c in columns]
    parts: list[Any] = []
    if table.title:
        parts.append(table.title if isinstance(table.title, Text) else Text.from_markup(
            str(table.title), style="italic"))
    for row in range(table.row_count):
        heading = cells[0][row] if columns else ""
        label = f"{headers[0]} {_plain(heading)}" if headers[0] and is_numeric(
            [heading]) else heading
        if parts:
            parts.append(Text(""))
        parts.append(Text.from_markup(label, style="bold") if isinstance(label, str)
                     else label)
        grid = Table.grid(padding=(0, 1, 0, 2))
        grid.add_column(no_wrap=True)
        grid.add_column(overflow="fold")
        for header, column in zip(headers[1:], cells[1:]):
            grid.add_row(Text(f"{header}:" if header else ""), column[row])
        parts.append(grid)
    if table.caption:
        parts.append(Text.from_markup(str(table.caption), style="dim"))
    return Group(*parts)


class FitTables(RenderHook):
    """A render hook fitting each table printed on a console (:func:`fit_table`)."""

    def __init__(self, console: Console) -> None:
        self.console = console

    def process_renderables(self, renderables: list[ConsoleRenderable]
                            ) -> list[ConsoleRenderable]:
        return [fit_table(r, self.console) if isinstance(r, Table) else r
                for r in renderables]

# SPDX-License-Identifier: BSD-3-Clause
"""The hand tables of docs/ that bench/report.py checks its own numbers against: Markdown tables
read back from the doc pages, one dict per row (header cell -> row cell)."""
import os
import re


def tables_after(doc, heading_regex):
    """Every Markdown table in `doc` that follows the first line matching `heading_regex`, up to
    the next line that matches a Markdown heading; [] when the doc or the line is gone."""
    if not os.path.exists(doc):
        return []
    with open(doc) as f:
        lines = f.read().splitlines()
    start = next((i for i, l in enumerate(lines) if re.search(heading_regex, l)), None)
    if start is None:
        return []
    tables, current = [], []
    for line in lines[start + 1:]:
        if line.startswith("#"):
            break
        if line.startswith("|"):
            current.append([c.strip() for c in line.strip().strip("|").split("|")])
            continue
        if current:
            tables.append(current)
            current = []
    if current:
        tables.append(current)
    return [[dict(zip(t[0], row)) for row in t[2:]] for t in tables if len(t) > 2]


def first_table_after(doc, heading_regex):
    tables = tables_after(doc, heading_regex)
    return tables[0] if tables else []


def numbers(cell):
    """Every number in a table cell ("0.332 / 0.780" -> [0.332, 0.78])."""
    return [float(n) for n in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?",
                                         (cell or "").replace(",", ""))]


def number(cell):
    """The first number in a table cell ("0.71 (0.69)" -> 0.71), None when there is none."""
    m = re.search(r"-?[\d.]+(?:e[-+]?\d+)?", cell.replace(",", "")) if cell else None
    return float(m.group(0)) if m else None

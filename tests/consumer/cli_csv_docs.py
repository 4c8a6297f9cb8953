#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The program's CSVs against the docs' column tables, so that neither drifts from the other.

    cli_csv_docs.py WORK_DIR DOCS_DIR

Every *.csv under WORK_DIR (the outputs of the runs cli_csv_docs.cmake made) must be one of the tables below, and
the docs page that documents it has a heading "#### `<file>.csv`" followed by a table whose rows read
"| `<column>` | <unit>, <step> | <meaning> |". Checked:
- every column the program wrote is a row of the table, and every row is a column of some file of that name;
- the unit is in the column's name (m: _m, m²: _m2, CRS unit: _crs, degrees: _deg, kWh/m²: kwh_m2, kWh: _kwh,
  %: _pct, share: _fraction, s: _s);
- every number written has exactly the decimals of the documented step (0.001: 3, ...), and a column documented
  without a step ("—", "0/1") holds no decimal number.
"""
import csv
import pathlib
import re
import sys

PAGES = {
    "waterbodies.csv": "waterbodies.md",
    "scores.csv": "waterbodies.md",
    "roof_patches.csv": "pv.md",
    "footprints.csv": "pv.md",
    "roof_scores.csv": "pv.md",
    "summary.csv": "solar.md",
    "dsm_outliers.csv": "solar.md",
    "facade_patches.csv": "solar.md",
    "surface_table.csv": "solar.md",
    "bill_savings.csv": "solar.md",
    "hydro_bodies.csv": "hydro-flattening.md",
    "hydro_qa.csv": "hydro-flattening.md",
}
# The unit a documented column states -> what its name must hold (a regex on the name).
UNIT_NAMES = [
    (r"^m²", r"_m2$"),
    (r"^m,", r"_m$"),
    (r"^CRS unit", r"_crs$"),
    (r"^degrees", r"_deg$"),
    (r"^kWh/m²", r"kwh_m2"),
    (r"^kWh,", r"_kwh$"),
    (r"^kW,", r"(^|_)kwp$"),
    (r"^%", r"_pct$"),
    (r"^share", r"_fraction$"),
    (r"^s,", r"_s$"),
]
ROW = re.compile(r"^\| `([a-z0-9_]+)` \| ([^|]*) \| [^|]+ \|$")
DECIMAL = re.compile(r"^-?[0-9]+\.([0-9]+)$")


def doc_tables(docs: pathlib.Path):
    """{csv name: {column: unit cell}} from the "#### `name.csv`" sections of the pages."""
    tables = {}
    for page in sorted(set(PAGES.values())):
        current = None
        for line in (docs / page).read_text(encoding="utf-8").splitlines():
            if line.startswith("#"):
                m = re.match(r"^#### `([a-z_]+\.csv)`$", line)
                current = m.group(1) if m else None
                if current:
                    if current in tables:
                        sys.exit(f"{page}: `{current}` is documented twice")
                    tables[current] = {"page": page, "columns": {}}
                continue
            if current:
                m = ROW.match(line)
                if m:
                    tables[current]["columns"][m.group(1)] = m.group(2).strip()
    return tables


def main():
    work, docs = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    tables = doc_tables(docs)
    problems = []
    for name, page in PAGES.items():
        if name not in tables or not tables[name]["columns"]:
            problems.append(f"{page}: no column table under a heading #### `{name}`")
    seen = {}
    files = sorted(work.rglob("*.csv"))
    for path in files:
        name = path.name
        if name not in PAGES:
            problems.append(f"{path}: a CSV the docs' tables do not know (add it to PAGES and to its page)")
            continue
        documented = tables.get(name, {}).get("columns", {})
        page = PAGES[name]
        with path.open(newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        if not rows:
            problems.append(f"{path}: empty")
            continue
        header, data = rows[0], rows[1:]
        seen.setdefault(name, set()).update(header)
        for col in header:
            if col not in documented:
                problems.append(f"{path}: column `{col}` is not in the table of {page}")
        for col, unit in documented.items():
            for unit_re, name_re in UNIT_NAMES:
                if re.match(unit_re, unit) and not re.search(name_re, col):
                    problems.append(f"{page}: `{col}` is in {unit} but its name does not say so ({name_re})")
        for r, row in enumerate(data, start=2):
            if len(row) != len(header):
                problems.append(f"{path}:{r}: {len(row)} fields, the header {len(header)}")
                continue
            for col, field in zip(header, row):
                unit = documented.get(col)
                if unit is None:
                    continue
                step = re.search(r", (0\.0*1|1)$", unit)
                m = DECIMAL.match(field)
                if step:
                    want = len(step.group(1)) - 2 if "." in step.group(1) else 0
                    if field and not m and not re.match(r"^-?[0-9]+$", field):
                        problems.append(f"{path}:{r}: `{col}` = '{field}' is not a number")
                    elif m and len(m.group(1)) != want:
                        problems.append(f"{path}:{r}: `{col}` = {field} has {len(m.group(1))} decimals, "
                                        f"{page} says {want} (step {step.group(1)})")
                elif m:
                    problems.append(f"{path}:{r}: `{col}` = {field} is a decimal number; {page} gives it no step")
    for name, written in seen.items():
        for col in tables.get(name, {}).get("columns", {}):
            if col not in written:
                problems.append(f"{PAGES[name]}: `{name}` documents `{col}`, which no run wrote")
    for name in PAGES:
        if name not in seen:
            problems.append(f"no run wrote {name}: the check cannot see its columns")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"{len(files)} CSV files of {len(seen)} kinds: every column documented with its unit and rounding")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes the options reference of docs/getting-started.md from the headers.

For each options struct below, one table lists its fields in declaration order with the type, the default and
the header's own comment (which states the unit and the valid range). The tables go between the markers
<!-- options-tables: begin --> and <!-- options-tables: end --> of the page:

    python3 tests/docs/options_tables.py            # rewrite the tables in docs/getting-started.md
    python3 tests/docs/options_tables.py --check    # exit 1 if the page's tables differ from the headers

The ctest docs_snippets compiles the tables too (tests/docs/extract_snippets.cmake): field names, their order
and the defaults written in backticks must match the structs.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "getting-started.md"
BEGIN, END = "<!-- options-tables: begin -->", "<!-- options-tables: end -->"

# (section title, [struct names]) in the order of the page.
STRUCTS = [
    ("Running", ["execution"]),
    ("Points to rasters", ["rasterize_options", "class_selection"]),
    ("Filters, morphology, labels, statistics",
     ["angular_filter_options", "morphology_options", "connected_components_options", "idw_fill_options",
      "slope_aspect_options", "ks_one_sided_options"]),
    ("Sun, shadows, sky view", ["sun_position_options", "raylines_shadow_options", "horizon_map_options",
                                "sky_view_factor_options", "clear_sky_options", "irradiance_record"]),
    ("Solar irradiation", ["solar_site", "irradiance_maps_options", "sky_options", "perez_diffuse_options"]),
    ("Waterbodies", ["extract_waterbodies_options"]),
    ("Hydro-flattening", ["hydro_flatten_options", "channel_join_options", "lake_level_options", "river_profile_options",
                          "lower_to_banks_options"]),
    ("Buildings", ["extract_buildings_options", "ground_model_options", "building_candidates_options",
                   "local_planes_options", "grow_roof_surfaces_options", "merge_roof_surfaces_options",
                   "vegetation_by_returns_options", "building_rim_options", "roof_under_crowns_options", "party_walls_options",
                   "morphological_ground_options"]),
    ("Rooftop PV", ["roof_suitability_options", "roof_planes_options", "azimuth_mode_select_options",
                    "roof_yield_options"]),
]


def strip_comment(line):
    """The code of a line, without a trailing // comment (string literals do not occur in options)."""
    i = line.find("//")
    return line if i < 0 else line[:i]


def find_struct(name):
    """(path, body lines) of `struct name {` in a public header (detail/ headers only when nowhere else)."""
    headers = sorted((ROOT / "include").rglob("*.hpp"), key=lambda p: ("/detail/" in str(p), str(p)))
    pattern = re.compile(r"^struct " + re.escape(name) + r"\s*\{")
    for path in headers:
        lines = path.read_text().splitlines()
        for i, line in enumerate(lines):
            if pattern.match(line):
                body, depth = [], 0
                for line2 in lines[i:]:
                    code = strip_comment(line2)
                    body.append(line2)
                    depth += code.count("{") - code.count("}")
                    if depth == 0 and "}" in code:
                        return path.relative_to(ROOT), body[1:-1]
    raise SystemExit(f"options_tables.py: struct {name} not found in include/")


def split_top(text, sep=","):
    """Splits at `sep` outside brackets."""
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch in "<({[":
            depth += 1
        elif ch in ">)}]":
            depth -= 1
        if ch == sep and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    parts.append(cur)
    return [p.strip() for p in parts]


def members(body):
    """[(type, name, default or None, comment)] of the data members at the struct's top level. A declaration may
    span lines (a braced default); its ///< comments, and ///< lines right below it, are its comment; a /// block
    above it is its comment too."""
    out, pending, last = [], [], None
    stmt, stmt_comment, depth = "", [], 0
    for line in body:
        code = strip_comment(line).strip()
        m = re.search(r"///<?\s?(.*)$", line)
        comment = m.group(1).strip() if m else None
        trailing = comment is not None and "///<" in line
        if not stmt and not code:
            if trailing and last is not None:  # continuation of the member above
                last[3] = (last[3] + " " + comment).strip()
            elif comment is not None:
                pending.append(comment)
            else:
                pending, last = [], None
            continue
        stmt = stmt + (" " if stmt and not stmt.endswith(("{", "(", "<")) else "") + code
        if trailing:
            stmt_comment.append(comment)
        depth += code.count("{") - code.count("}")
        if depth > 0 or not (stmt.endswith(";") or stmt.endswith("}")):
            continue
        statement, text = stmt, " ".join(pending + stmt_comment)
        stmt, stmt_comment, pending, last = "", [], [], None
        head = statement.split("=")[0].split("{")[0]
        if not statement.endswith(";") or re.search(r"\w\s*\(", head) or re.match(r"(struct|class|enum|using)\b", head):
            continue  # a member function, a nested type or an alias
        m = re.match(r"^((?:const\s+)?[\w:]+(?:<.*?>)?)\s+(.*);$", statement)
        if not m:
            continue
        type_, decls = m.group(1), split_top(m.group(2))
        for decl in decls:
            d = re.match(r"^(\w+)\s*(?:=\s*(.*)|\{(.*)\})?$", decl, re.S)
            if not d:
                raise SystemExit(f"options_tables.py: cannot read member '{decl}'")
            default = d.group(2) if d.group(2) is not None else d.group(3)
            last = [type_, d.group(1), default, text]
            out.append(last)
    return out


def default_cell(default):
    if default is None:
        return "(none)"
    if default in ("NAN", "std::numeric_limits<double>::quiet_NaN()", "std::numeric_limits<float>::quiet_NaN()"):
        return "NaN"
    if default == "":
        return "`{}`"
    return "`" + default + "`"


def tables():
    out = [BEGIN, ""]
    for title, names in STRUCTS:
        out += [f"### {title}", ""]
        for name in names:
            path, body = find_struct(name)
            out += [f"#### `lidarfx::{name}`", "", f"In `{path.as_posix().removeprefix('include/')}`.", "",
                    "| field | default | type | meaning, unit, range (the header's comment) |", "|---|---|---|---|"]
            documented = None  # the last field with a comment: a comment above several fields covers them all
            for type_, field, default, text in members(body):
                if text:
                    documented = field
                elif documented:
                    text = f"(as `{documented}`)"
                else:
                    text = "—"
                text = text.replace("|", "\\|")
                out.append(f"| `{field}` | {default_cell(default)} | `{type_}` | {text} |")
            out.append("")
    out.append(END)
    return "\n".join(out)


def main():
    page = PAGE.read_text()
    if BEGIN not in page or END not in page:
        raise SystemExit(f"options_tables.py: {PAGE} has no {BEGIN} ... {END} markers")
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    new = head + tables() + tail
    if "--check" in sys.argv[1:]:
        if new != page:
            print("docs/getting-started.md: the options tables differ from the headers; "
                  "run python3 tests/docs/options_tables.py")
            return 1
        return 0
    PAGE.write_text(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())

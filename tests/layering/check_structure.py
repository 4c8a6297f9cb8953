#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Structure rules of docs/architecture.md that the include-line check (check_layers.cmake) cannot see.

  check_structure.py detail <include dir>     a header uses a `detail` name (qualified, or unqualified from inside
                                              its own namespace detail) only when it is declared in its own
                                              area (core/, adapters/, tiling/, kernels/<area>/, pipelines/<area>/,
                                              each with its detail/ folder) or in core/, the library's shared base
  check_structure.py length <include dir> N   no function body in a header is longer than N lines
  check_structure.py diary <docs dir> <file>…  user docs state the current truth: no work-log dates, sessions or
                                              numbered runs outside docs/history/
  check_structure.py std_includes <dir>…      every header includes the standard header of each std:: name it
                                              uses, itself (not through another header)

Each violation is printed as "<file>:<line>: <what>"; the exit status is 1 when there is one.
"""
import pathlib
import re
import sys


def strip_comments_and_strings(text):
    """The text with comments and string/char literals blanked (newlines kept, so line numbers hold)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c == '"' or c == "'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def area_of(header, root):
    parts = header.relative_to(root).parts
    if parts[0] in ("kernels", "pipelines"):
        return parts[0] + "/" + parts[1]
    return parts[0]


STATEMENT_WORDS = {"return", "co_return", "co_yield", "throw", "else", "case", "new", "delete", "sizeof", "do",
                   "typename", "template", "operator", "goto"}


KEYWORDS = set("""alignas alignof and asm auto bool break case catch char char8_t char16_t char32_t class concept const
consteval constexpr constinit const_cast continue co_await co_return co_yield decltype default delete do double
dynamic_cast else enum explicit export extern false float for friend goto if inline int long mutable namespace new
noexcept not nullptr operator or private protected public register reinterpret_cast requires return short signed
sizeof static static_assert static_cast struct switch template this thread_local throw true try typedef typeid
typename union unsigned using virtual void volatile wchar_t while final override""".split())


def detail_top_level_names(text):
    """Names declared directly inside the `namespace detail` blocks of a header (functions, types, constants;
    not their parameters or locals)."""
    names = set()
    for m in re.finditer(r"namespace\s+(?:lidarfx::)?detail\s*\{", text):
        depth, i, top = 1, m.end(), []
        while depth and i < len(text):
            c = text[i]
            if c == "{":
                depth += 1
                top.append(" {")
            elif c == "}":
                depth -= 1
            elif depth == 1:
                top.append(c)
            i += 1
        segment = "".join(top)
        while True:  # parameter lists out, their parentheses kept
            stripped = re.sub(r"\([^()]*\)", "()", segment)
            stripped = stripped.replace("()", "\0")
            if stripped == segment.replace("()", "\0"):
                break
            segment = stripped.replace("\0", "()")
        segment = segment.replace("\0", "()")
        for d in re.finditer(r"(\b[A-Za-z_]\w*|[>)])\s+([A-Za-z_]\w*)\s*(?=[(<{=;\[])", segment):
            if d.group(1) not in STATEMENT_WORDS:
                names.add(d.group(2))
        for d in re.finditer(r"\b(?:struct|class|enum)\s+([A-Za-z_]\w*)(?!\s*[,>=])|\b(?:using|concept)\s+([A-Za-z_]\w*)",
                             segment):  # a template's `class T,` or `class T>` is a parameter, not a type
            names.add(d.group(1) or d.group(2))
    return names


def check_detail(include_dir):
    root = pathlib.Path(include_dir) / "lidarfx"
    headers = sorted(p for p in root.rglob("*.hpp") if p.name != "lidarfx.hpp")
    code = {h: strip_comments_and_strings(h.read_text()) for h in headers}
    declared = {}  # area -> set of names written unqualified (declarations and same-namespace uses)
    for h, text in code.items():
        names = declared.setdefault(area_of(h, root), set())
        # a declaration: the name after a type (a word that is not a statement keyword, or the > or ) that ends one), followed
        # by what starts a function, a variable or a template; calls and uses do not declare
        for m in re.finditer(r"(\b[A-Za-z_]\w*|[>)])\s+([A-Za-z_]\w*)\s*(?=[(<{=;,\[])", text):
            if m.group(1) not in STATEMENT_WORDS:
                names.add(m.group(2))
        for m in re.finditer(r"\b(?:struct|class|using|enum|concept)\s+([A-Za-z_]\w*)", text):
            names.add(m.group(1))
    internal = {}  # area -> names declared at the top level of its `namespace detail` blocks
    for h, text in code.items():
        internal.setdefault(area_of(h, root), set()).update(detail_top_level_names(text))
    violations = []
    for h, text in code.items():
        area = area_of(h, root)
        own = declared.get(area, set()) | declared.get("core", set())
        # an unqualified use of another area's internal name (from inside a `namespace detail` block)
        for m in re.finditer(r"(?<![\w:.>])([A-Za-z_]\w*)\b", text):
            name = m.group(1)
            if name in own or name in KEYWORDS:
                continue
            owners = sorted(a for a, names in internal.items() if a not in (area, "core") and name in names)
            if owners:
                line = text.count("\n", 0, m.start()) + 1
                violations.append(f"lidarfx/{h.relative_to(root)}:{line}: {name} is internal to {', '.join(owners)}"
                                  f", not {area}: make it a documented public kernel in the right layer")
        for m in re.finditer(r"\bdetail::([A-Za-z_]\w*)", text):
            name = m.group(1)
            if name in declared.get(area, set()) or name in declared.get("core", set()):
                continue
            owners = sorted(a for a, names in declared.items() if name in names)
            line = text.count("\n", 0, m.start()) + 1
            violations.append(f"lidarfx/{h.relative_to(root)}:{line}: detail::{name} belongs to "
                              f"{', '.join(owners) or 'no area'}, not {area}: make it a documented public "
                              "kernel in the right layer, or keep it inside its area")
    return violations


def check_length(include_dir, limit):
    violations = []
    root = pathlib.Path(include_dir)
    for h in sorted(root.rglob("*.hpp")):
        text = strip_comments_and_strings(h.read_text())
        stack = []  # (line of '{', is a function body)
        line = 1
        for i, c in enumerate(text):
            if c == "\n":
                line += 1
            elif c == "{":
                head = text[max(0, i - 300):i]
                head = head[max(head.rfind(";"), head.rfind("{"), head.rfind("}")) + 1:]
                is_function = (re.search(r"\)\s*(const\s*)?(noexcept(\([^)]*\))?\s*)?(->[^{]*)?(requires[^{]*)?$", head)
                               and not re.search(r"\b(if|for|while|switch|catch)\s*\(", head)
                               and not re.search(r"\[[^\]]*\]\s*(\([^)]*\))?\s*(mutable\s*)?(->[^{]*)?$", head))
                stack.append((line, bool(is_function)))
            elif c == "}" and stack:
                start, is_function = stack.pop()
                if is_function and line - start + 1 > limit:
                    violations.append(f"{h}:{start}: function body of {line - start + 1} lines (at most {limit}): "
                                      "split it into named steps")
    return violations


DIARY = [
    (re.compile(r"\b20\d\d-\d\d-\d\d\b"), "a work-log date"),
    (re.compile(r"\b(first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|tenth|\d+(st|nd|rd|th))\s+"
                r"(reporting|tuning)\s+run\b", re.I), "a numbered run"),
    (re.compile(r"\b(reporting|tuning)\s+run\s+\d+\b", re.I), "a numbered run"),
    (re.compile(r"\b(this|last|previous|next)\s+session\b", re.I), "a session"),
    (re.compile(r"\bDESIGN\b|\.\./shared\b"), "a file outside the repository"),
    (re.compile(r"\bissues?\s+#?\d+", re.I), "a tracker issue number"),
]


def check_diary(docs_dir, files):
    violations = []
    paths = [pathlib.Path(f) for f in files] + sorted(pathlib.Path(docs_dir).rglob("*.md"))
    for p in paths:
        if "history" in p.parts:
            continue
        for number, text in enumerate(p.read_text().split("\n"), 1):
            for pattern, what in DIARY:
                if pattern.search(text):
                    violations.append(f"{p}:{number}: {what} in a user doc: state the current truth "
                                      "(history belongs in git or docs/history/)")
    return violations


# The standard header(s) that declare each std:: name the headers use; a file must include one of them itself.
# A name not listed is reported, so the table grows with the code rather than silently passing it.
_STD_HEADERS = {
    "cstddef": "size_t ptrdiff_t byte nullptr_t",
    "cstdint": "int8_t int16_t int32_t int64_t uint8_t uint16_t uint32_t uint64_t uintptr_t intptr_t",
    "vector": "vector", "array": "array", "span": "span", "map": "map", "set": "set", "list": "list",
    "unordered_map": "unordered_map",
    "queue": "priority_queue queue",
    "string": "string to_string", "string_view": "string_view", "optional": "optional nullopt",
    "limits": "numeric_limits", "numbers": "numbers", "chrono": "chrono", "bit": "bit_cast popcount bit_width "
    "countr_zero countl_zero bit_floor bit_ceil has_single_bit", "numeric": "iota accumulate reduce inner_product",
    "cmath": "cos sin tan acos asin atan atan2 sqrt hypot exp log log10 log2 pow abs fabs floor ceil round lround "
    "llround nearbyint rint fmod fmin fmax isfinite isnan isinf copysign nextafter",
    "algorithm": "min max clamp sort stable_sort nth_element fill fill_n copy copy_n all_of any_of none_of unique "
    "max_element min_element minmax_element lower_bound upper_bound binary_search partition_point transform find find_if count "
    "count_if reverse ranges",
    "utility": "move forward swap exchange pair declval cmp_less cmp_greater cmp_less_equal cmp_greater_equal",
    "type_traits": "is_arithmetic_v is_same_v is_floating_point_v is_integral_v is_const_v is_signed_v "
    "is_nothrow_default_constructible_v is_invocable_v is_invocable_r_v invoke_result_t remove_cvref_t remove_cv_t conditional_t "
    "make_signed_t true_type false_type",
    "concepts": "convertible_to same_as integral floating_point invocable", "memory": "unique_ptr make_unique "
    "make_unique_for_overwrite allocator", "functional": "function invoke greater less", "tuple": "tuple tie get",
    "thread": "thread this_thread", "mutex": "mutex lock_guard unique_lock",
    "condition_variable": "condition_variable",
    "atomic": "atomic memory_order_relaxed memory_order_acquire memory_order_release",
    "cstring": "memcpy memset memcmp", "cstdlib": "malloc free abs", "sstream": "ostringstream ios",
    "ios": "ios", "stdexcept": "runtime_error invalid_argument logic_error out_of_range",
    "new": "bad_alloc bad_array_new_length", "exception": "exception_ptr current_exception rethrow_exception exception",
    "initializer_list": "initializer_list",
}
STD_HEADERS_OF = {}
for _header, _names in _STD_HEADERS.items():
    for _name in _names.split():
        STD_HEADERS_OF.setdefault(_name, set()).add(_header)
# Names whose declaration comes with any of several headers by the standard's own synopsis.
for _name, _also in {"get": "utility array", "initializer_list": "vector array map set list string unordered_map",
                     "erase_if": "vector map set list string unordered_map", "string_view": "string",
                     "ranges": "ranges"}.items():
    STD_HEADERS_OF.setdefault(_name, set()).update(_also.split())


def check_std_includes(dirs):
    violations = []
    for d in dirs:
        for h in sorted(pathlib.Path(d).rglob("*.hpp")):
            raw = h.read_text()
            included = set(re.findall(r"^\s*#\s*include\s*<([a-z_0-9]+)>", raw, re.M))
            text = strip_comments_and_strings(raw)
            reported = set()
            for number, line in enumerate(text.split("\n"), 1):
                for name in re.findall(r"\bstd::([A-Za-z_0-9]+)", line):
                    if name in reported:
                        continue
                    wanted = STD_HEADERS_OF.get(name)
                    if wanted is None:
                        violations.append(f"{h}:{number}: std::{name} is not in check_structure.py's table of "
                                          "standard headers: add it")
                    elif not wanted & included:
                        violations.append(f"{h}:{number}: std::{name} is used but <{min(wanted)}> is not included")
                    else:
                        continue
                    reported.add(name)
    return violations


def main(argv):
    if len(argv) >= 2 and argv[0] == "detail":
        violations = check_detail(argv[1])
    elif len(argv) == 3 and argv[0] == "length":
        violations = check_length(argv[1], int(argv[2]))
    elif len(argv) >= 2 and argv[0] == "std_includes":
        violations = check_std_includes(argv[1:])
    elif len(argv) >= 2 and argv[0] == "diary":
        violations = check_diary(argv[1], argv[2:])
    else:
        print(__doc__, file=sys.stderr)
        return 2
    for v in violations:
        print(v)
    print(f"{len(violations)} violation(s)")
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

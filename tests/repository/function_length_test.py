#!/usr/bin/env python3
"""Fails when a C++ function in common/, server/ or client/ is over 150 lines.

A function is counted from the first line of its declaration to the line of
its closing brace. The scan matches braces after blanking comments, string
and character literals (raw strings too) and preprocessor lines, so braces
in text never count; a brace at namespace or class level opens a function
body when what precedes it has a parameter list and is neither a type, an
initializer (`=`) nor a member's brace initializer in a constructor's list.

Usage: function_length_test.py --repo DIR
"""

import argparse
import pathlib
import re
import sys

MAX_LINES = 150
FOLDERS = ("common", "server", "client")

# Functions known to be over the limit, "path:name", each to be split and
# then removed from here. None today.
KNOWN_LONG = set()


def strip_code(text):
    """Comments, literals' contents and preprocessor lines as spaces.

    Every line keeps its number, and quotes stay so that `extern "C"` still
    reads as one.
    """
    out = list(text)
    i, n = 0, len(text)
    at_line_start = True

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if at_line_start and c == "#":
            # A preprocessor line, with its continuations.
            j = i
            while j < n and (text[j] != "\n" or text[j - 1] == "\\"):
                j += 1
            wipe(i, j)
            i = j
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            wipe(i, j)
            i = j
        elif c == '"':
            prefix = re.search(r"(?:u8|[uUL])?R$", text[max(0, i - 3):i])
            before = i - (len(prefix.group(0)) if prefix else 0) - 1
            if prefix and (before < 0 or not (text[before].isalnum() or text[before] == "_")):
                # A raw string: R"delim( ... )delim".
                open_paren = text.index("(", i)
                close = ")" + text[i + 1:open_paren] + '"'
                j = text.find(close, open_paren)
                j = n if j < 0 else j + len(close)
                wipe(i + 1, j - 1)
                i = j
            else:
                j = i + 1
                while j < n and text[j] != '"':
                    j += 2 if text[j] == "\\" else 1
                wipe(i + 1, j)
                i = j + 1
        elif c == "'":
            # A digit separator (1'000) follows a number; a literal does not.
            k = i
            while k > 0 and (text[k - 1].isalnum() or text[k - 1] in "_.'"):
                k -= 1
            if k < i and text[k].isdigit():
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            wipe(i + 1, j)
            i = j + 1
        else:
            i += 1
    return "".join(out)


TYPE_HEAD = re.compile(r"^(?:template\s*<.*?>\s*)?(?:class|struct|union|enum)\b", re.S)
NAMESPACE_HEAD = re.compile(r"^(?:inline\s+)?namespace\b|^extern\s*\"\s*\"$")
ACCESS = re.compile(r"^(?:public|private|protected)\s*:(?!:)\s*")
NAME = re.compile(r"((?:[A-Za-z_]\w*\s*::\s*)*(?:operator\s*[^\s(]+|~?[A-Za-z_]\w*))\s*$")


def group_end(head, opening, closing):
    """Index just past the first top-level `opening`...`closing` group of
    `head`, or -1."""
    depth = 0
    for k, c in enumerate(head):
        if c == opening:
            depth += 1
        elif c == closing:
            depth -= 1
            if depth == 0:
                return k + 1
    return -1


def without_template(head):
    """`head` less a leading template <...> clause."""
    end = group_end(head, "<", ">") if head.startswith("template") else -1
    return head[end:].lstrip() if end >= 0 else head


def classify(head):
    """What a `{` at namespace or class level preceded by `head` opens.

    'namespace' and 'type' hold declarations; 'function' is a body;
    'nested' is a brace inside the declaration, which goes on after it (a
    default argument's {} in the parameter list, a member's brace
    initializer in a constructor's list); anything else is an
    'initializer'.
    """
    head = ACCESS.sub("", head.strip())
    if head.count("(") > head.count(")"):
        return "nested"
    if NAMESPACE_HEAD.search(head):
        return "namespace"
    if TYPE_HEAD.search(head):
        return "type"
    head = without_template(head)
    if "operator" not in head and re.search(r"(?<![=!<>])=(?!=)", head.split("(")[0]):
        return "initializer"
    params_end = group_end(head, "(", ")")
    if params_end < 0:
        return "initializer"
    rest = head[params_end:]
    if re.match(r"^[\s\w&]*:(?!:)", rest) and re.search(r"[\w>]$", rest):
        return "nested"
    return "function"


def function_name(head):
    head = ACCESS.sub("", head.strip())
    open_paren = head.find("(")
    match = NAME.search(head[:open_paren])
    return re.sub(r"\s+", "", match.group(1)) if match else head[:open_paren].strip()


def long_functions(text):
    """(name, first line, lines) of each function over MAX_LINES in `text`."""
    code = strip_code(text)
    found = []
    # Scopes: each entry is (kind, start offset of the declaration that
    # opened a function body, or of the pending declaration).
    stack = [["namespace", 0]]
    head_start = 0
    for pos, c in enumerate(code):
        kind = stack[-1][0]
        in_declarations = kind in ("namespace", "type")
        if c == "{":
            if in_declarations:
                opened = classify(code[head_start:pos])
                stack.append([opened, head_start])
                if opened in ("namespace", "type"):
                    head_start = pos + 1
            else:
                stack.append(["block", pos])
        elif c == "}":
            if len(stack) == 1:
                continue  # unbalanced: ignore rather than crash
            closed, start = stack.pop()
            if closed == "function":
                head = code[start:pos]
                first = start + len(head) - len(head.lstrip())
                first_line = code.count("\n", 0, first) + 1
                lines = code.count("\n", 0, pos) + 1 - first_line + 1
                if lines > MAX_LINES:
                    found.append((function_name(code[first:code.index("{", first)]),
                                  first_line, lines))
            if closed != "nested" and stack[-1][0] in ("namespace", "type"):
                head_start = pos + 1
        elif c == ";" and in_declarations:
            head_start = pos + 1
        elif c == ":" and in_declarations and ACCESS.fullmatch(code[head_start:pos + 1].strip()):
            head_start = pos + 1
    return found


def self_check():
    """The scanner on snippets whose answers are known; a list of failures."""
    body = "\n".join(["  x++;"] * MAX_LINES)
    cases = {
        # Braces in strings, characters, raw strings and comments.
        'int F() {\n  s = "}}";\n  c = \'}\';\n  r = R"x(})x";\n  // }\n  /* } */\n' + body
        + "\n}\n": [("F", 1, MAX_LINES + 7)],
        # Digit separators are no character literals.
        "int G() {\n  n = 1'000;\n" + body + "\n  c = '{';\n}\n": [("G", 1, MAX_LINES + 4)],
        # A constructor's brace initializers, in a class in a namespace.
        "namespace a {\nclass C {\n public:\n  C() : x_{1}, y_(2) {\n" + body
        + "\n  }\n};\n}  // namespace a\n": [("C", 4, MAX_LINES + 2)],
        # A default argument's braces; a template's default argument.
        "C::C(Options o = {}) : x_(o) {\n" + body + "\n}\n"
        "template <int k = 1>\nvoid K() {\n" + body + "\n}\n":
        [("C::C", 1, MAX_LINES + 2), ("K", MAX_LINES + 3, MAX_LINES + 3)],
        # Exactly at the limit passes; an initializer is no function.
        "void H() {\n" + "\n".join(["  x++;"] * (MAX_LINES - 2)) + "\n}\n"
        "const int k[] = {\n" + body + "\n};\n": [],
        # A macro with a brace is no scope.
        "#define OPEN {\nvoid J() {\n" + body + "\n}\n": [("J", 2, MAX_LINES + 2)],
    }
    failures = []
    for snippet, expected in cases.items():
        got = long_functions(snippet)
        if got != expected:
            failures.append(f"self-check: expected {expected}, got {got} on:\n{snippet[:120]}")
    return failures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True, type=pathlib.Path)
    args = parser.parse_args()
    failures = self_check()
    seen_known = set()
    for folder in FOLDERS:
        for path in sorted((args.repo / folder).rglob("*")):
            if path.suffix not in (".cc", ".h"):
                continue
            rel = path.relative_to(args.repo).as_posix()
            for name, line, lines in long_functions(path.read_text(encoding="utf-8")):
                key = f"{rel}:{name}"
                if key in KNOWN_LONG:
                    seen_known.add(key)
                    print(f"known: {rel}:{line}: {name} is {lines} lines")
                    continue
                failures.append(f"{rel}:{line}: {name} is {lines} lines (at most {MAX_LINES})")
    for key in sorted(KNOWN_LONG - seen_known):
        failures.append(f"{key} is listed in KNOWN_LONG but no longer over {MAX_LINES} "
                        "lines: remove it from the list")
    for failure in failures:
        print(failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Fails when a proto of the API (proto/haptics/v1) uses proto3 `optional`.

The protos install with the client SDK for clients in other languages,
and older protoc releases and some code generators refuse proto3
`optional` (docs/sdk.md, Protos for other toolchains): a field that needs
presence says so with a has-flag beside it instead.

Usage: plain_proto3_test.py --repo DIR
"""

import argparse
import pathlib
import re
import sys

# A field label at the start of a statement (comments are stripped first).
OPTIONAL = re.compile(r"(^|[;{])\s*optional\s+\w", re.MULTILINE)


def uses_optional(text):
    """The line numbers where `text` (a .proto file) labels a field optional."""
    code = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.DOTALL)
    code = re.sub(r"//[^\n]*", "", code)
    return [code.count("\n", 0, m.end()) + 1 for m in OPTIONAL.finditer(code)]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True)
    repo = pathlib.Path(parser.parse_args().repo)
    # The check's own oracle: a labelled field is found, a comment is not.
    assert uses_optional("message M {\n  // optional x = 1;\n  optional double x = 1;\n}") == [3]
    failures = []
    protos = sorted((repo / "proto" / "haptics" / "v1").glob("*.proto"))
    for proto in protos:
        for line in uses_optional(proto.read_text(encoding="utf-8")):
            failures.append(f"{proto.relative_to(repo)}:{line}: proto3 optional")
    for failure in failures:
        print(failure)
    print(f"{len(protos)} protos read, {len(failures)} optional fields")
    return 1 if failures or not protos else 0


if __name__ == "__main__":
    sys.exit(main())

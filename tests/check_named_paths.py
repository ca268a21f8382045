#!/usr/bin/env python3
"""Every path the project names must exist: repository paths named in source comments, --help texts
and docstrings, the same paths named in the text of README.md and docs/ (from the repository root or
the page's folder), and relative links and images in README.md and docs/.

A named path is a token such as docs/reference/lyapunov.md, scripts/test.sh or chaos/choose.hpp (an include
path, looked up under the include directories too). Exits 1 listing each missing path with the file
and line that names it.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1])
TOP = ("docs", "scripts", "references", "chaos", "mechanism", "study", "python", "tests", "bench", "cmake", "support")
NAMED = re.compile(r"(?<![\w./-])((?:%s)/[\w./+-]*\w\.(?:md|sh|py|hpp|cpp|h|tsv|toml|txt|json|in|cmake))" % "|".join(TOP))
INCLUDE_DIRS = ["", "chaos/include/", "chaos/models/include/", "chaos/models/src/", "mechanism/include/", "study/include/", "chaos/src/", "chaos/commands/", "tests/"]
SOURCES = ("*.cpp", "*.hpp", "*.h", "*.py", "*.sh", "*.in", "CMakeLists.txt", "*.cmake", "*.toml")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def exists(name):
    return any((ROOT / (d + name)).exists() for d in INCLUDE_DIRS)


def tracked(patterns, under):
    for pattern in patterns:
        for path in (ROOT / under).rglob(pattern):
            if not any(part in ("build", "build-sanitize", ".git", "node_modules") or part.startswith("build")
                       for part in path.relative_to(ROOT).parts):
                yield path


def main():
    missing = []
    files = set()
    for top in ("chaos", "mechanism", "study", "python", "bench", "tests", "scripts", "cmake", "support"):
        files.update(tracked(SOURCES, top))
    files.update(p for p in [ROOT / "CMakeLists.txt"] if p.exists())
    for path in sorted(files):
        if path.name == "check_named_paths.py":
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            for name in NAMED.findall(line):
                name = name.rstrip(".")
                if "*" in name or "$" in name or "<" in name:
                    continue
                if not exists(name):
                    missing.append(f"{path.relative_to(ROOT)}:{number}: names {name}, which does not exist")
    pages = [ROOT / "README.md"] + sorted((ROOT / "docs").rglob("*.md"))
    for page in pages:
        for number, line in enumerate(page.read_text(errors="replace").splitlines(), 1):
            for name in NAMED.findall(line):
                name = name.rstrip(".")
                if "*" in name or "$" in name or "<" in name:
                    continue
                if not exists(name) and not (page.parent / name).exists():
                    missing.append(f"{page.relative_to(ROOT)}:{number}: names {name}, which does not exist")
            for target in LINK.findall(line):
                if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                    continue  # a web address or an anchor on the same page
                relative = target.split("#", 1)[0]
                if relative and not (page.parent / relative).exists():
                    missing.append(f"{page.relative_to(ROOT)}:{number}: links {target}, which does not exist")
    for m in missing:
        print(m)
    if missing:
        print(f"{len(missing)} named path(s) missing")
        return 1
    print(f"every named path exists ({len(files)} source files, {len(pages)} pages)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

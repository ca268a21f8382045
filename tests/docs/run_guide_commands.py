#!/usr/bin/env python3
"""Runs the shell commands of the user's guide (README.md and docs/guide/*.md) and of the reference
pages (docs/reference/, fenced blocks only) as written, against the built commands, and fails if any
exits non-zero or does not print the output a page shows.

    run_guide_commands.py REPO CHAOS MECHANISM STUDY

The commands of a page are the lines of its code blocks (docs/README.md, "Commands in the guide
are tested", says the same for those who write the pages):

- in a fenced block without a language (```), the lines that start with `$ ` (the prompt); the
  lines after them, up to the next prompt, are the output shown, and each must be printed (on
  standard output or error) by the command: a line as it stands, or, where it holds `...` (text
  left out), a printed line holding its pieces in that order; a line that is only `...` stands for
  lines left out. The comparison ignores blanks at either end of a line, and a line of names (as
  `ls` shows them in columns) also matches the same names printed one per line;
- in an indented block (four blanks), every line;
- a line ending in `\\` continues on the next; a `# comment` after a command stays (the shell drops
  it);
- a command ending in `echo "exit $?"` must print the `exit N` line the block shows after it.

A page runs in a temporary directory of its own, block after block, so a file one command writes
(`lorenz.dat`) is there for the next. `chaos`, `mechanism` and `study` are the built commands (on
PATH), and so are `build/chaos/chaos`, `build/mechanism/mechanism` and `build/study/study`. An HTML
comment on the line before a block, invisible on the page, changes how the block runs:

    <!-- guide-test: skip: REASON -->      the block is not run (needs root, a network, MPI, minutes)
    <!-- guide-test: instead: COMMAND -->  COMMAND runs in the block's place: a shorter run of the
                                           same command (the full one takes too long for a test)
    <!-- guide-test: before: COMMAND -->   COMMAND runs first (it makes a file the block reads)

Several comments may stand before one block. Each command runs under `bash -o pipefail` with a
limit of LIMIT seconds (GUIDE_TEST_LIMIT, default 60); the run fails on the first non-zero exit,
naming the page, the line and the command, with its standard error.
"""
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

MARKER = re.compile(r"^<!--\s*guide-test:\s*(skip|instead|before):\s*(.*?)\s*-->\s*$")


def blocks(text):
    """The code blocks of a page: (first line number, 'fenced' or 'indented', lines, markers)."""
    lines = text.split("\n")
    out = []
    markers = []
    i = 0
    previous_blank = True
    while i < len(lines):
        line = lines[i]
        m = MARKER.match(line.strip())
        if m:
            markers.append((m.group(1), m.group(2)))
            i += 1
            continue
        if line.startswith("```"):
            language = line[3:].strip()
            start = i + 1
            body = []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            i += 1
            if not language:
                out.append((start + 1, "fenced", body, markers))
            markers = []
            previous_blank = False
            continue
        # An indented block: after a blank line, not inside a list item's continuation (a list
        # item's text is indented by two blanks, a block by four).
        if line.startswith("    ") and line.strip() and previous_blank:
            start = i + 1
            body = []
            while i < len(lines) and (lines[i].startswith("    ") or not lines[i].strip()):
                body.append(lines[i][4:])
                i += 1
            while body and not body[-1].strip():
                body.pop()
            out.append((start, "indented", body, markers))
            markers = []
            previous_blank = True
            continue
        if line.strip():
            markers = [] if not line.strip().startswith("<!--") else markers
        previous_blank = not line.strip()
        i += 1
    return out


def shown_output(body, k):
    """The output a fenced block shows after the command ending on body[k]: the lines up to the
    next prompt, without those that are only `...` and without blank ones."""
    out = []
    for later in body[k + 1:]:
        if later.startswith("$ "):
            break
        if later.strip() and later.strip() != "...":
            out.append(later.rstrip())
    return out


def missing_lines(shown, printed):
    """The shown lines that no printed line matches (see the module's docstring)."""
    printed = [p.strip() for p in printed]
    whole = set(printed)
    missing = []
    for line in shown:
        if "..." not in line:
            words = line.split()
            # `ls` prints names in columns on a terminal and one per line into a pipe.
            listed = any(printed[i:i + len(words)] == words for i in range(len(printed)))
            if line.strip() not in whole and not listed:
                missing.append(line)
            continue
        pieces = [piece.strip() for piece in line.split("...") if piece.strip()]

        def holds(p):
            at = 0
            for piece in pieces:
                at = p.find(piece, at)
                if at < 0:
                    return False
                at += len(piece)
            return True

        if not any(holds(p) for p in printed):
            missing.append(line)
    return missing


def commands(kind, body, first):
    """The commands of a block as (line number, command, shown exit, shown output), continuation
    lines joined. The shown exit is the `exit N` line a fenced block prints after a command ending
    in `echo "exit $?"` (command-line.md shows the exit codes so), checked against the run; else
    None. The shown output is what shown_output gives (fenced blocks; indented ones show none)."""
    out = []
    k = 0
    while k < len(body):
        line = body[k]
        number = first + k
        if kind == "fenced":
            if not line.startswith("$ "):
                k += 1
                continue
            line = line[2:]
        elif not line.strip():
            k += 1
            continue
        text = line
        while text.rstrip().endswith("\\") and k + 1 < len(body):
            k += 1
            text = text.rstrip()[:-1] + " " + body[k].strip()
        shown = None
        if kind == "fenced" and text.rstrip().endswith('echo "exit $?"'):
            for later in body[k + 1:]:
                if later.startswith("$ "):
                    break
                if re.fullmatch(r"exit \d+", later.strip()):
                    shown = later.strip()
                    break
        out.append((number, text.strip(), shown, shown_output(body, k) if kind == "fenced" else []))
        k += 1
    return out


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    repo, chaos, mechanism, study = (Path(a).resolve() for a in sys.argv[1:])
    limit = float(os.environ.get("GUIDE_TEST_LIMIT", "60"))
    guide = [repo / "README.md"] + sorted((repo / "docs" / "guide").glob("*.md"))
    # The reference pages show commands in fenced blocks only; their indented blocks are code and
    # formulas, not commands.
    reference = sorted((repo / "docs" / "reference").rglob("*.md"))
    pages = guide + reference
    if not pages:
        sys.exit(f"{repo}/docs/guide: no pages")
    failures = 0
    ran = 0
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="guide-test-") as scratch:
        bin_dir = Path(scratch) / "bin"
        bin_dir.mkdir()
        for name, target in (("chaos", chaos), ("mechanism", mechanism), ("study", study)):
            (bin_dir / name).symlink_to(target)
        env = dict(os.environ, PATH=f"{bin_dir}:{os.environ.get('PATH', '/usr/bin:/bin')}", LC_ALL="C")
        for page in pages:
            work = Path(scratch) / str(page.relative_to(repo)).replace("/", "_")
            work.mkdir()
            for name, target in (("chaos", chaos), ("mechanism", mechanism), ("study", study)):
                (work / "build" / name).mkdir(parents=True)
                (work / "build" / name / name).symlink_to(target)
            for first, kind, body, markers in blocks(page.read_text(encoding="utf-8")):
                if any(k == "skip" for k, _ in markers) or (page in reference and kind != "fenced"):
                    continue
                planned = [(first - 1, v, None, []) for k, v in markers if k == "before"]
                instead = [(first - 1, v, None, []) for k, v in markers if k == "instead"]
                planned += instead if instead else commands(kind, body, first)
                for number, command, shown, output in planned:
                    ran += 1
                    t0 = time.monotonic()
                    try:
                        r = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=work, env=env,
                                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                           stderr=subprocess.PIPE, timeout=limit)
                        code, err = r.returncode, r.stderr.decode("utf-8", "replace")
                        printed = r.stdout.decode("utf-8", "replace").split("\n")
                        if code == 0 and shown and shown not in printed:
                            code, err = "0, but", f"the page shows '{shown}', the run printed: {' | '.join(printed)[-300:]}"
                        elif code == 0 and output:
                            missing = missing_lines(output, printed + err.split("\n"))
                            if missing:
                                code, err = "0, but", ("the run does not print these lines the page shows:\n  " +
                                                      "\n  ".join(m[:200] for m in missing[:8]))
                    except subprocess.TimeoutExpired:
                        code, err = "timeout", f"ran past {limit:g} s (GUIDE_TEST_LIMIT)"
                    seconds = time.monotonic() - t0
                    where = f"{page.relative_to(repo)}:{number}"
                    if code != 0:
                        failures += 1
                        print(f"FAIL {where}: exit {code}: {command}\n{err.strip()[-1500:]}", file=sys.stderr)
                    else:
                        print(f"ok   {where} ({seconds:.1f} s): {command[:110]}")
    print(f"{ran} commands from {len(pages)} pages, {failures} failed, {time.monotonic() - started:.0f} s")
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())

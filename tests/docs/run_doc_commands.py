#!/usr/bin/env python3
"""Runs every shell command written in README.md, docs/*.md and samples/*/README.md.

The convention (README.md, "Commands in the docs"):

* A fenced block marked ```sh holds commands: every line runs, except blank lines
  and comment lines; a line ending in a backslash continues on the next one.
* A fenced block marked ```console is a session: lines starting with "$ " are
  commands and run (their output, the other lines, is shown to the reader, not
  compared).
* An HTML comment `<!-- not run in CI: REASON -->` on the line just above such a
  block skips it; the reason is listed in the summary.
* Every other block names what it holds (```text for synopses, messages and
  output, ```json, ```cpp, ...) and is not run. A block with no language is an
  error: nobody could tell whether it is meant to run.
* A sh block this script cannot run as written (a syntax error, a "$ " prompt,
  a synopsis placeholder such as [--opt] or "...") is an error.

Each document gets a fresh scratch folder holding a copy of the committed samples/
(git ls-files, new files too; the whole folder outside a git checkout) and links to
scripts/, bench/ and the build under test (as build/); `ssid` on PATH is the
build's. Its commands run in that folder one after the other, each in its own
`sh -c` (files persist between the commands of one document, shell variables and
`cd` do not). Steps that build the tree (./scripts/install-deps, cmake -S . -B
build, cmake --build build, ctest --test-dir build; the test command's
./scripts/sanitize-tests and ./scripts/fuzz-smoke N) are stood in for by the build
under test and counted, not run: the test command builds it and .ci/run runs that.

Exit status 0 when every command ran with status 0 and every block could be read;
1 otherwise, with the document, line, command and its stderr for each failure.
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

SKIP_MARK = re.compile(r"^<!--\s*not run in CI:\s*(.*?)\s*-->$")
FENCE = re.compile(r"^(```+|~~~+)\s*([^\s`]*)")
COMMAND_LANGS = ("sh", "console")
# Languages that would be commands under another name: one name for one thing.
ALIASES = ("bash", "shell", "shell-session", "zsh")
# A synopsis or a note, not a command: optional brackets around an option, an ellipsis.
PLACEHOLDER = re.compile(r"\[-|\[[A-Z]|\.\.\.|<[A-Za-z]")
# An indented (unfenced) code line that reads as a command.
INDENTED_COMMAND = re.compile(r"^ {4,}(\$ |ssid |build/|\./|cmake |ctest )")
# Steps that build the tree: the build under test stands for them. The sanitizer
# suite and the fuzz smoke of README's test command build trees of their own and
# are CI's own steps (.ci/run runs them), not commands a document shows.
BUILD_STEP = re.compile(
    r"^(\./scripts/install-deps|cmake -S \. -B build\b|cmake --build build\b|ctest --test-dir build\b"
    r"|\./scripts/sanitize-tests$|\./scripts/fuzz-smoke \d+$)")


class Command:
    def __init__(self, doc, line, text, block_line):
        self.doc, self.line, self.text, self.block_line = doc, line, text, block_line


def docs_of(source):
    files = ["README.md"] + sorted(glob.glob("docs/*.md", root_dir=source)) + \
        sorted(glob.glob("samples/*/README.md", root_dir=source))
    return [f for f in files if os.path.isfile(os.path.join(source, f))]


def join_continuations(numbered):
    """(line number, text) pairs -> commands, a trailing backslash joining a line to the next."""
    out, pending, start = [], "", None
    for n, text in numbered:
        if start is None:
            start = n
        if text.endswith("\\"):
            pending += text[:-1] + " "
            continue
        out.append((start, pending + text))
        pending, start = "", None
    if start is not None:
        out.append((start, pending.rstrip() + " \\"))  # left open: reported by the syntax check
    return out


def split_and(text):
    """Splits a command at the top-level `&&` (outside quotes and $(...))."""
    parts, cur, quote, depth, i = [], "", None, 0, 0
    while i < len(text):
        c = text[i]
        if quote:
            if c == "\\" and quote == '"' and i + 1 < len(text):
                cur += text[i:i + 2]
                i += 2
                continue
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif text.startswith("$(", i):
            depth += 1
        elif c == ")" and depth:
            depth -= 1
        elif text.startswith("&&", i) and depth == 0:
            parts.append(cur.strip())
            cur, i = "", i + 2
            continue
        cur += c
        i += 1
    parts.append(cur.strip())
    return parts


def read_blocks(source, doc):
    """-> (commands, skipped [(doc, line, reason)], errors [message], blocks run)."""
    lines = open(os.path.join(source, doc), encoding="utf-8").read().split("\n")
    commands, skipped, errors, blocks = [], [], [], 0
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            if INDENTED_COMMAND.match(lines[i]) and (i == 0 or lines[i - 1].strip() == "" or
                                                     lines[i - 1].startswith("    ")):
                errors.append(f"{doc}:{i + 1}: a command in an indented code block: use a fenced block "
                              "(sh, console or text) so that it is run or said not to be")
            i += 1
            continue
        fence, lang, start = m.group(1), m.group(2), i + 1
        j = i + 1
        while j < len(lines) and not (lines[j].startswith(fence[0] * len(fence))
                                      and lines[j].strip(fence[0]) == ""):
            j += 1
        if j == len(lines):
            errors.append(f"{doc}:{start}: fenced block never closed")
            break
        body = [(start + 1 + k, t.rstrip()) for k, t in enumerate(lines[i + 1:j])]
        i = j + 1
        where = f"{doc}:{start}"
        if lang == "":
            errors.append(f"{where}: fenced block without a language: mark it sh (commands, run in CI), "
                          "console ($ lines run in CI) or text (synopsis, message, output; not run)")
            continue
        if lang in ALIASES:
            errors.append(f"{where}: ```{lang}: commands are marked ```sh (or ```console for a session)")
            continue
        if lang not in COMMAND_LANGS:
            continue
        k = start - 2
        while k >= 0 and lines[k].strip() == "":
            k -= 1
        mark = SKIP_MARK.match(lines[k].strip()) if k >= 0 else None
        if mark:
            if not mark.group(1):
                errors.append(f"{doc}:{k + 1}: 'not run in CI' needs a reason")
            skipped.append((where, mark.group(1)))
            continue
        if lang == "sh":
            own = [(n, t.strip()) for n, t in body if t.strip() and not t.strip().startswith("#")]
        else:
            own, in_cmd = [], False
            for n, t in body:
                if t.startswith("$ "):
                    own.append((n, t[2:].strip()))
                    in_cmd = t.endswith("\\")
                elif in_cmd:
                    own.append((n, t.strip()))
                    in_cmd = t.endswith("\\")
            if not own:
                errors.append(f"{where}: console block with no '$ ' command line: mark it text")
                continue
        cmds = join_continuations(own)
        bad = False
        for n, text in cmds:
            problem = None
            if text.startswith("$ "):
                problem = "a '$ ' prompt in a sh block (a session with output is a console block)"
            elif PLACEHOLDER.search(text):
                problem = "a synopsis placeholder ([--option], [NAME], ..., <name>): mark the block text"
            else:
                check = subprocess.run(["sh", "-n", "-c", text], capture_output=True, text=True)
                if check.returncode != 0:
                    problem = "not valid sh: " + check.stderr.strip()
            if problem:
                errors.append(f"{doc}:{n}: cannot run `{text}`: {problem}")
                bad = True
        if bad:
            continue
        blocks += 1
        commands += [Command(doc, n, text, start) for n, text in cmds]
    return commands, skipped, errors, blocks


def scratch_for(root, doc, source, build, ssid):
    d = os.path.join(root, re.sub(r"[^A-Za-z0-9_.-]", "_", doc))
    os.makedirs(d)
    # The samples git knows of (committed or new, not ignored): a file a script left in the tree
    # (samples/estimate/nominal.bdf) must not make a doc that names it pass here and fail
    # on a fresh clone.
    listed = subprocess.run(["git", "-C", source, "ls-files", "-z", "--cached", "--others", "--exclude-standard",
                             "samples"], capture_output=True)
    if listed.returncode == 0 and listed.stdout:
        for rel in listed.stdout.decode().split("\0"):
            if rel and os.path.isfile(os.path.join(source, rel)):  # not one deleted since the last commit
                os.makedirs(os.path.join(d, os.path.dirname(rel)), exist_ok=True)
                shutil.copy2(os.path.join(source, rel), os.path.join(d, rel))
    else:
        shutil.copytree(os.path.join(source, "samples"), os.path.join(d, "samples"), symlinks=True)
    for name in ("scripts", "bench"):
        os.symlink(os.path.join(source, name), os.path.join(d, name))
    os.symlink(build, os.path.join(d, "build"))
    bin_dir = os.path.join(d, ".bin")
    os.makedirs(bin_dir)
    os.symlink(ssid, os.path.join(bin_dir, "ssid"))
    return d, bin_dir


def tail(text, n=30):
    lines = text.rstrip().split("\n")
    return "\n".join(("    " + x) for x in lines[-n:]) if text.strip() else "    (nothing)"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--source", required=True, help="repository root")
    ap.add_argument("--build", required=True, help="the build folder under test (build/ in the docs)")
    ap.add_argument("--ssid", required=True, help="the built ssid executable (ssid in the docs)")
    ap.add_argument("--only", nargs="*", default=[], help="documents to run (paths from the root)")
    ap.add_argument("--list", action="store_true", help="print the commands, run nothing")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folders")
    ap.add_argument("--without-bench", action="store_true",
                    help="skip the commands of build/bench/ (a build with SSID_BUILD_BENCH=OFF)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds one command may take")
    a = ap.parse_args()
    source, build, ssid = (os.path.realpath(p) for p in (a.source, a.build, a.ssid))

    docs = docs_of(source)
    if a.only:
        unknown = [d for d in a.only if d not in docs]
        if unknown:
            print("not a document of the convention: " + ", ".join(unknown), file=sys.stderr)
            return 1
        docs = a.only

    plan, skipped, errors, blocks = [], [], [], 0
    for doc in docs:
        c, s, e, b = read_blocks(source, doc)
        plan.append((doc, c))
        skipped += s
        errors += e
        blocks += b

    # .ci/run must run exactly README's test command (its last sh block).
    readme = [c for d, cmds in plan if d == "README.md" for c in cmds]
    ci = os.path.join(source, ".ci", "run")
    if readme and os.path.isfile(ci):
        ci_lines = [x.strip() for x in open(ci, encoding="utf-8").read().split("\n")]
        if readme[-1].text not in ci_lines:
            errors.append(f"README.md:{readme[-1].line}: .ci/run does not run README's test command as written: "
                          f"`{readme[-1].text}`")

    if a.list:
        for doc, cmds in plan:
            for c in cmds:
                print(f"{c.doc}:{c.line}: {c.text}")
        for where, why in skipped:
            print(f"{where}: skipped: {why}")
        for e in errors:
            print(e)
        return 1 if errors else 0

    root = tempfile.mkdtemp(prefix="ssid_docs_")
    failures, ran, stood_in, no_bench = [], 0, 0, 0
    t0 = time.monotonic()
    for doc, cmds in plan:
        if not cmds:
            continue
        d, bin_dir = scratch_for(root, doc, source, build, ssid)
        env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ.get("PATH", ""))
        env.pop("SSID", None)
        td = time.monotonic()
        for c in cmds:
            for part in split_and(c.text):
                if BUILD_STEP.match(part):
                    stood_in += 1
                    continue
                if a.without_bench and part.startswith("build/bench/"):
                    no_bench += 1
                    continue
                ran += 1
                tc = time.monotonic()
                try:
                    r = subprocess.run(["sh", "-c", part], cwd=d, env=env, capture_output=True, text=True,
                                       errors="replace", timeout=a.timeout, stdin=subprocess.DEVNULL)
                    code, err, out = r.returncode, r.stderr, r.stdout
                except subprocess.TimeoutExpired as x:
                    code = f"timeout after {a.timeout:g} s"
                    err = x.stderr or ""
                    if isinstance(err, bytes):  # TimeoutExpired keeps the raw bytes
                        err = err.decode(errors="replace")
                    out = ""
                dt = time.monotonic() - tc
                if code != 0:
                    failures.append(f"{c.doc}:{c.line}: `{part}` exited {code} ({dt:.1f} s); stderr:\n{tail(err)}"
                                    + (f"\n  stdout (end):\n{tail(out, 10)}" if out.strip() else ""))
                    print(f"FAIL {c.doc}:{c.line} ({dt:.1f} s)", flush=True)
                    break  # the rest of a `&&` chain would not run either
        print(f"{doc}: {len(cmds)} command line(s), {time.monotonic() - td:.1f} s", flush=True)
    if not a.keep:
        shutil.rmtree(root, ignore_errors=True)
    else:
        print(f"scratch folders kept in {root}")

    print(f"\nran {ran} command(s) from {blocks} block(s) of {len(docs)} document(s) in "
          f"{time.monotonic() - t0:.1f} s; {stood_in} build step(s) stood in for by the build under test; "
          + (f"{no_bench} benchmark command(s) not run (built without the benchmarks); " if no_bench else "")
          + f"{len(skipped)} block(s) skipped:")
    for where, why in skipped:
        print(f"  {where}: {why}")
    for e in errors:
        print(f"ERROR {e}")
    for f in failures:
        print(f"FAILED {f}")
    if errors or failures:
        print(f"\n{len(failures)} command(s) failed, {len(errors)} block(s) could not be read")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

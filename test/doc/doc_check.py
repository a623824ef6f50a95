#!/usr/bin/env python3
"""The docs stay true (ctest doc_check, test/tests.cmake).

(a) Every relative link in README.md and doc/*.md (doc/pending/ left out) resolves to an
    existing file, and every #anchor to a heading of its target (GitHub's slug rule).
(b) The fenced ```bash blocks of the README's "Quick start" section (and its ```python blocks,
    through /usr/bin/python3) run, in order, as one bash script (set -e) in a temporary directory, against the workspace MBK_WS, on a ROS
    master of the test's own (a free port); after each block the commands it left running
    (ending in `&`) are stopped with SIGTERM (a background job of a non-interactive shell ignores SIGINT). The whole script must end within --timeout s.

Usage: doc_check.py [--root DIR] [--links-only] [--timeout S]
"""
import argparse
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^(```|~~~)")
LINK = re.compile(r"(?<!\!)\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)|!\[[^\]]*\]\(([^)\s]+)\)")


def strip_code(text):
    """The text outside fenced blocks and inline code spans."""
    out, fenced = [], False
    for line in text.split("\n"):
        if FENCE.match(line.strip()):
            fenced = not fenced
            out.append("")
            continue
        out.append("" if fenced else re.sub(r"`[^`]*`", "", line))
    return "\n".join(out)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation but - and _ dropped, spaces to -."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip()).lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen, out = {}, set()
    for line in strip_code_keep_headings(open(path, encoding="utf-8").read()):
        s = slug(line)
        n = seen.get(s, 0)
        seen[s] = n + 1
        out.add(s if n == 0 else "%s-%d" % (s, n))
    return out


def strip_code_keep_headings(text):
    fenced = False
    for line in text.split("\n"):
        if FENCE.match(line.strip()):
            fenced = not fenced
        elif not fenced and re.match(r"^#{1,6} ", line):
            yield line.lstrip("#").strip()


def doc_files(root):
    files = [os.path.join(root, "README.md")]
    doc = os.path.join(root, "doc")
    files += sorted(os.path.join(doc, f) for f in os.listdir(doc) if f.endswith(".md"))
    return files


def check_links(root):
    errors = []
    for path in doc_files(root):
        text = strip_code(open(path, encoding="utf-8").read())
        for lineno, line in enumerate(text.split("\n"), 1):
            for m in LINK.finditer(line):
                target = m.group(1) or m.group(2)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, mailto: ...
                    continue
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                where = "%s:%d: link %s" % (os.path.relpath(path, root), lineno, target)
                if not os.path.exists(dest):
                    errors.append("%s: no file %s" % (where, os.path.relpath(dest, root)))
                elif anchor and (not dest.endswith(".md") or anchor not in anchors(dest)):
                    errors.append("%s: no heading with anchor #%s in %s" % (where, anchor, os.path.relpath(dest, root)))
    return errors


def quick_start_blocks(readme):
    """The ```bash blocks of the README section whose heading starts with 'Quick start', and its
    ```python blocks as bash running them with /usr/bin/python3."""
    blocks, section, block, language = [], None, None, None
    for line in open(readme, encoding="utf-8").read().split("\n"):
        if block is not None:
            if line.strip().startswith("```"):
                text = "\n".join(block)
                blocks.append(text if language == "bash" else
                              "/usr/bin/python3 - <<'MBK_PYTHON_BLOCK'\n%s\nMBK_PYTHON_BLOCK" % text)
                block = None
            else:
                block.append(line)
        elif re.match(r"^#{1,6} ", line):
            section = line.lstrip("#").strip()
        elif (section and section.lower().startswith("quick start") and
              line.strip() in ("```bash", "```python")):
            block, language = [], line.strip()[3:]
    return blocks


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def script_of(blocks):
    parts = ["set -e", "stop() { for j in $(jobs -p); do kill -TERM $j 2>/dev/null || true; done; wait || true; }",
             "trap stop EXIT"]
    for i, block in enumerate(blocks):
        parts.append("echo '--- quick start block %d' >&2" % (i + 1))
        parts.append(block)
        parts.append("stop")
    return "\n".join(parts) + "\n"


def run_quick_start(root, ws, timeout):
    blocks = quick_start_blocks(os.path.join(root, "README.md"))
    if not blocks:
        return ["README.md: no ```bash block in the Quick start section"]
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_HOSTNAME="127.0.0.1")
    env["PATH"] = "/usr/bin:" + env.get("PATH", "")
    setup = os.path.join(ws, "devel", "setup.bash")
    with tempfile.TemporaryDirectory() as tmp:
        env["ROS_HOME"] = tmp
        master = subprocess.Popen(["roscore", "-p", str(port)], env=env, cwd=tmp,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        try:
            for _ in range(100):
                if subprocess.call(["rostopic", "list"], env=env, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL) == 0:
                    break
                time.sleep(0.2)
            script = "source %s\n" % setup + script_of(blocks)
            proc = subprocess.Popen(["bash", "-c", script], env=env, cwd=tmp, start_new_session=True)
            try:
                rc = proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGINT)
                time.sleep(2)
                os.killpg(proc.pid, signal.SIGKILL)
                return ["README.md Quick start: did not finish within %g s (a command that waits for "
                        "something that never comes?)" % timeout]
            if rc != 0:
                return ["README.md Quick start: a command failed (exit %d; see the output above)" % rc]
        finally:
            os.killpg(master.pid, signal.SIGINT)
            try:
                master.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(master.pid, signal.SIGKILL)
    return []


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(here)))
    ap.add_argument("--links-only", action="store_true")
    ap.add_argument("--timeout", type=float, default=45)
    args = ap.parse_args()
    errors = check_links(args.root)
    if not args.links_only:
        ws = os.environ.get("MBK_WS")
        if not ws:
            errors.append("MBK_WS is not set: the workspace whose devel/setup.bash the quick start uses")
        else:
            errors += run_quick_start(args.root, ws, args.timeout)
    for e in errors:
        print("doc_check: " + e, file=sys.stderr)
    print("doc_check: %s" % ("FAILED, %d problem(s)" % len(errors) if errors else "ok"))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())

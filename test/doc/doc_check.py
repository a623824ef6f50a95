#!/usr/bin/env python3
"""The docs stay true (ctest doc_check, test/tests.cmake).

(a) Every relative link in README.md and doc/*.md (doc/pending/ left out) resolves to an
    existing file, and every #anchor to a heading of its target (GitHub's slug rule).
(b) The fenced ```bash blocks of the README's "Quick start" section (and its ```python blocks,
    through /usr/bin/python3) run, in order, as one bash script (set -e) in a temporary directory, against the workspace MBK_WS, on a ROS
    master of the test's own (a free port); after each block the commands it left running
    (ending in `&`) are stopped with SIGTERM (a background job of a non-interactive shell ignores SIGINT). The whole script must end within --timeout s.
(c) With --pages (ctest doc_pages): every ```sh, ```bash and ```python block of doc/*.md runs as
    written, each from a fresh shell that has sourced the workspace only (bash -e; python blocks
    through /usr/bin/python3), in a fresh folder of its own (not the repository), on a ROS
    master of the check's own, on an Xvfb screen (rviz:=true); --jobs blocks at once (the
    longest first), each on a master and a screen of its own. The folder holds the reader's own
    files the pages name (FIXTURES: copies of the repository's real data). A command that runs
    until the reader stops it (roslaunch, rostopic echo, rviz) passes when it is still running
    after --settle s with no node died and no error printed, and is then stopped (SIGTERM, as
    the reader's Ctrl-C). An HTML comment on the line before a block may say
    `<!-- doc_check: first COMMAND -->` (run before the block: what the page's text says is
    already there, e.g. a bringup's robot_description), `<!-- doc_check: beside COMMAND -->`
    (started before the block and stopped after it: the running node the block talks to) or
    `<!-- doc_check: skip REASON -->` (not run: a cluster, a clone, a file's content; listed).

Usage: doc_check.py [--root DIR] [--links-only] [--pages [--only REGEX] [--jobs N]] [--timeout S]
                    [--settle S]
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


# The reader's own files the pages name, made in each block's folder (doc_check --pages).
FIXTURES = {
    "walk.bvh": "test/mocap/131_01.bvh",  # a motion capture file
    "run.bag": "test/fuzz/seeds/bag/human_10_samples.bag",  # joint states of the human body
    "more.bag": "test/fuzz/seeds/bag/human_10_samples.bag",
    "robot.urdf": "config/human_body.urdf",  # the reader's robot (run.bag's)
    "my_robot.urdf": "config/human_body.urdf",
    "list.txt": None,  # a list of recordings: walk.bvh
    "trials/131_01.bvh": "test/mocap/131_01.bvh",  # a folder of recordings
    "logs/run.bag": "test/fuzz/seeds/bag/human_10_samples.bag",
}
# A trajectory CSV of the human body scene (config/human_body.yaml): every coordinate, the pelvis
# rising 1 mm a sample.
MOCAP_CSV = r"""/usr/bin/python3 - <<'MBK_CSV' > mocap.csv
import subprocess, mb_kinematics
pkg = subprocess.check_output(["rospack", "find", "mb_kinematics"], text=True).strip()
names = mb_kinematics.load(pkg + "/config/human_body.yaml").coordinate_names
print(",".join(("time",) + names))
for i in range(20):
    print(",".join(["%g" % (0.01 * (i + 1))] + ["%g" % (0.001 * i if n == "root/z" else 0) for n in names]))
MBK_CSV"""
DIRECTIVE = re.compile(r"^<!--\s*doc_check:\s*(first|beside|skip)\s+(.*?)\s*-->$")
# Commands that run until the reader stops them: shell functions of the same name run them in
# the background, wait --settle s, fail if they ended or printed an error, then stop them
# (SIGTERM: a background job of a non-interactive shell ignores SIGINT).
LONG_RUNNING = r"""
mbk_running() {
  local log; log=$(mktemp)
  "$@" >"$log" 2>&1 &
  local pid=$! waited=0
  while [ "$waited" -lt "$MBK_SETTLE" ] && kill -0 "$pid" 2>/dev/null; do sleep 1; waited=$((waited + 1)); done
  local alive=true; kill -0 "$pid" 2>/dev/null || alive=false
  # What it printed before the reader's Ctrl-C: a roslaunch still starting nodes on a loaded
  # machine says RLException when stopped, which is not the page's fault.
  local failed=false; grep -qE 'process has died|RLException|ERROR|FATAL|Traceback' "$log" && failed=true
  kill -TERM "$pid" 2>/dev/null; wait "$pid" 2>/dev/null || true
  if ! $alive || $failed; then
    cat "$log" >&2; echo "doc_check: '$*' ended or failed within $MBK_SETTLE s" >&2; rm -f "$log"; return 1
  fi
  rm -f "$log"; echo "doc_check: '$*' ran $MBK_SETTLE s, stopped" >&2
}
roslaunch() { mbk_running command roslaunch "$@"; }
rviz() { mbk_running command rviz "$@"; }
rostopic() { if [ "$1" = echo ] && [[ " $* " != *" -n "* ]]; then mbk_running command rostopic "$@"; else command rostopic "$@"; fi; }
"""
# A command of a block that LONG_RUNNING runs until stopped (settle_waits).
LONG_COMMAND = re.compile(r"(?:^|[;&|(]\s*|\bthen\s+)"
                          r"(?:roslaunch|rviz|rostopic echo(?![^\n]* -n ))\b", re.M)


def page_blocks(path):
    """(line, language, text, directives) of every ```sh/```bash/```python block of a page."""
    blocks, lines = [], open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^```(\w*)\s*$", lines[i])
        if not m:
            i += 1
            continue
        end = i + 1
        while not lines[end].startswith("```"):
            end += 1
        directives = []
        j = i - 1
        while j >= 0 and DIRECTIVE.match(lines[j].strip()):
            directives.insert(0, DIRECTIVE.match(lines[j].strip()).groups())
            j -= 1
        if m.group(1) in ("sh", "bash", "python"):
            blocks.append((i + 1, m.group(1), "\n".join(lines[i + 1:end]), directives))
        i = end + 1
    return blocks


def block_script(root, setup, language, text, directives):
    """The bash script that runs one block from a fresh shell in the current folder."""
    parts = ["source %s" % setup, "set -e"]
    for name, source in FIXTURES.items():
        if source:
            parts.append("mkdir -p $(dirname %s) && cp %s %s" % (name, os.path.join(root, source), name))
    parts.append(MOCAP_CSV)
    parts.append("echo walk.bvh > list.txt")
    parts.append("beside=()")
    for kind, command in directives:
        if kind == "first":
            parts.append(command)
        elif kind == "beside":
            parts.append("%s >beside.log 2>&1 & beside+=($!); sleep $((3 * MBK_SETTLE))" % command)
    parts.append("trap 'for p in \"${beside[@]}\"; do kill -TERM $p 2>/dev/null; done; wait' EXIT")
    parts.append(LONG_RUNNING)  # after the directives' commands, which run as they are
    if language == "python":
        parts.append("/usr/bin/python3 - <<'MBK_PYTHON_BLOCK'\n%s\nMBK_PYTHON_BLOCK" % text)
    else:
        parts.append(text)
    return "\n".join(parts) + "\n"


def start_xvfb(env):
    """An Xvfb screen for rviz:=true (None when Xvfb is not installed)."""
    r, w = os.pipe()
    try:
        xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1280x900x24",
                                 "-nolisten", "tcp"], pass_fds=(w,), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
    except FileNotFoundError:
        return None
    os.close(w)
    with os.fdopen(r) as f:
        env["DISPLAY"] = ":" + f.readline().strip()
    return xvfb


def fresh_parameters(master_uri):
    """The parameter server as roscore starts it: a block does not see the one before's."""
    import xmlrpc.client
    server = xmlrpc.client.ServerProxy(master_uri)
    for _ in range(100):
        try:
            names = server.getParamNames("/doc_check")[2]
            break
        except OSError:
            time.sleep(0.2)
    for name in names:
        if name not in ("/run_id", "/rosdistro", "/rosversion"):
            server.deleteParam("/doc_check", name)


class Station:
    """What one worker runs blocks on: a ROS master, an Xvfb screen, a ROS_HOME and a HOME of its
    own, in a folder of its own."""

    def __init__(self, tmp, settle):
        self.folder = tempfile.mkdtemp(dir=tmp)
        self.port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % self.port,
                        ROS_HOSTNAME="127.0.0.1", MBK_SETTLE=str(settle),
                        ROS_HOME=os.path.join(self.folder, "ros"),
                        HOME=os.path.join(self.folder, "home"))
        self.env["PATH"] = "/usr/bin:" + self.env.get("PATH", "")
        os.makedirs(self.env["HOME"])
        self.xvfb = start_xvfb(self.env)
        self.master = subprocess.Popen(["roscore", "-p", str(self.port)], env=self.env,
                                       cwd=self.folder, stdout=subprocess.DEVNULL,
                                       stderr=subprocess.DEVNULL, start_new_session=True)

    def run(self, script, timeout):
        """(exit status or a reason, the block's output)."""
        fresh_parameters(self.env["ROS_MASTER_URI"])
        folder = tempfile.mkdtemp(dir=self.folder)
        with tempfile.TemporaryFile(mode="w+") as log:
            proc = subprocess.Popen(["bash", "-c", script], env=self.env, cwd=folder,
                                    stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            try:
                rc = proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                rc = "no end within %g s" % timeout
            log.seek(0)
            return rc, log.read()

    def close(self):
        os.killpg(self.master.pid, signal.SIGINT)
        self.master.wait()
        if self.xvfb:
            self.xvfb.terminate()
            self.xvfb.wait()


def settle_waits(text, directives):
    """How many --settle waits a block takes at least: three per command started beside it, one
    per command that runs until stopped (LONG_RUNNING)."""
    beside = sum(kind == "beside" for kind, _ in directives)
    return 3 * beside + len(LONG_COMMAND.findall(text))


def run_pages(root, ws, settle, timeout, only=None, jobs=3):
    """Every command block of doc/*.md (c), on JOBS stations at once (the blocks are independent:
    each has a fresh folder and a fresh parameter server; most of their time is the settle wait
    of a command that runs until stopped); a list of problems."""
    import queue
    import threading
    setup = os.path.join(ws, "devel", "setup.bash")
    todo, skipped, blocks = queue.Queue(), [], []
    for path in doc_files(root)[1:]:
        for line, language, text, directives in page_blocks(path):
            where = "%s:%d" % (os.path.relpath(path, root), line)
            if only and not re.search(only, where):
                continue
            skip = [d for k, d in directives if k == "skip"]
            if skip:
                skipped.append("%s (%s)" % (where, skip[0]))
                continue
            blocks.append((settle_waits(text, directives), where,
                           block_script(root, setup, language, text, directives)))
    # The longest blocks first (their settle waits), so that none starts last on its own.
    for _, where, script in sorted(blocks, key=lambda b: -b[0]):
        todo.put((where, script))
    ran = todo.qsize()
    errors, printing = [], threading.Lock()

    def work(station):
        while True:
            try:
                where, script = todo.get_nowait()
            except queue.Empty:
                return
            began = time.monotonic()
            rc, output = station.run(script, 4 * timeout)  # a block: several commands
            with printing:
                print("--- %s (%.0f s)\n%s" % (where, time.monotonic() - began, output),
                      file=sys.stderr, end="", flush=True)
                if rc != 0:
                    errors.append("%s: the block failed (%s; its output is above)" % (where, rc))

    with tempfile.TemporaryDirectory() as tmp:
        stations = [Station(tmp, settle) for _ in range(max(1, min(jobs, ran)))]
        try:
            workers = [threading.Thread(target=work, args=(s,), daemon=True) for s in stations]
            for w in workers:
                w.start()
            for w in workers:
                w.join()
        finally:
            for s in stations:
                s.close()
    print("doc_check: %d blocks of doc/*.md run; not run: %s" % (ran, "; ".join(skipped) or "none"))
    return sorted(errors)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(here)))
    ap.add_argument("--links-only", action="store_true")
    ap.add_argument("--pages", action="store_true", help="run the command blocks of doc/*.md")
    ap.add_argument("--timeout", type=float, default=45)
    ap.add_argument("--settle", type=int, default=12)  # a loaded machine: roslaunch still starting at 6 s
    ap.add_argument("--only", help="with --pages: the blocks whose FILE:LINE matches this regex")
    ap.add_argument("--jobs", type=int, default=3, help="with --pages: blocks run at once")
    args = ap.parse_args()
    # ctest's timeout (SIGTERM): the masters and screens are stopped on the way out.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("doc_check: stopped (SIGTERM)"))
    errors = check_links(args.root)
    if args.pages:
        ws = os.environ.get("MBK_WS")
        errors += (run_pages(args.root, ws, args.settle, args.timeout, args.only, args.jobs) if ws else
                   ["MBK_WS is not set: the workspace whose devel/setup.bash the pages use"])
    elif not args.links_only:
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

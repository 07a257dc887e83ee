#!/usr/bin/env python3
"""The documentation's commands, checked (J8): every ```sh block in README.md and docs/*.md says
on the line above its fence whether it is run here or why not:

    <!-- docs-check: run -->
    <!-- docs-check: run with-controller; /opt/hapticctrl => {scratch}/opt; expect out/*.png -->
    <!-- docs-check: manual: the reason -->

A block to run runs as written, under `bash -euo pipefail`, in a scratch directory that looks
like a checkout whose build is BUILD_DIR (`build` links to it, every other top-level entry to the
source), with each `A => B` replaced first ({scratch}: the scratch directory). `with-controller`
starts hapticctrl-core and hapticctrl-lcm for a private instance for the block's duration;
`expect GLOB` names what the block must have made (relative to the scratch directory).
A block without a marker, a marker without a block, or a block that fails fails the check.

usage: check_docs.py SOURCE_DIR BUILD_DIR [--list]
"""
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

MARKER = re.compile(r"^<!-- docs-check: (run|manual)(.*?) -->$")
BLOCK_TIMEOUT_S = 600


class Block:
    def __init__(self, path, line, text, kind, detail):
        self.path, self.line, self.text, self.kind = path, line, text, kind
        self.controller = False
        self.replacements = []
        self.expected = []
        self.reason = ""
        if kind == "manual":
            self.reason = detail.lstrip(":").strip()
            return
        for part in (p.strip() for p in detail.split(";")):
            if part == "with-controller":
                self.controller = True
            elif part.startswith("expect "):
                self.expected.append(part[len("expect "):].strip())
            elif "=>" in part:
                old, new = (x.strip() for x in part.split("=>", 1))
                self.replacements.append((old, new))
            elif part:
                raise ValueError(f"{self.where()}: unknown marker part '{part}'")

    def where(self):
        return f"{self.path}:{self.line}"


def documents(source):
    docs = os.path.join(source, "docs")
    names = sorted(n for n in os.listdir(docs) if n.endswith(".md"))
    return ["README.md"] + [os.path.join("docs", n) for n in names]


def blocks_of(source, path):
    """The file's ```sh blocks with their markers; errors for what is not marked."""
    lines = open(os.path.join(source, path), encoding="utf-8").read().split("\n")
    found, errors = [], []
    i = 0
    while i < len(lines):
        marker = MARKER.match(lines[i].strip())
        if lines[i].startswith("```sh"):
            errors.append(f"{path}:{i + 1}: a sh block without a docs-check marker on the line above")
        if marker:
            if i + 1 >= len(lines) or not lines[i + 1].startswith("```sh"):
                errors.append(f"{path}:{i + 1}: a docs-check marker not right above a sh block")
                i += 1
                continue
            end = i + 2
            while end < len(lines) and not lines[end].startswith("```"):
                end += 1
            try:
                found.append(Block(path, i + 2, "\n".join(lines[i + 2:end]), marker.group(1),
                                   marker.group(2)))
            except ValueError as e:
                errors.append(str(e))
            i = end
        i += 1
    return found, errors


def workspace(source, build):
    """A scratch directory that looks like the checkout, with `build` being BUILD_DIR."""
    scratch = tempfile.mkdtemp(prefix="hapticctrl-docs-")
    for name in os.listdir(source):
        if name not in ("build", ".git"):
            os.symlink(os.path.join(source, name), os.path.join(scratch, name))
    os.symlink(os.path.abspath(build), os.path.join(scratch, "build"))
    return scratch


def start_controller(build, scratch, env):
    """hapticctrl-core and hapticctrl-lcm for a private instance; returns their processes."""
    instance = f"docs{os.getpid()}"
    run_dir = os.path.join(scratch, "run")
    os.mkdir(run_dir, 0o700)
    env["HAPTICCTRL_RUNTIME_DIR"] = run_dir
    # Benchmark mode: a block is checked, not the machine's timing. A plain 1 ms core failed
    # safe on a stall of CI's VM before the block ran, in both attempts (2026-12-06), and the
    # recording it was to make was empty.
    core = subprocess.Popen(
        [os.path.join(build, "rt_core", "hapticctrl-core"), "--instance", instance, "--period-us",
         "1000", "--rt", "ignore", "--benchmark-mode", "--state-dir", run_dir],
        env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
        stderr=open(os.path.join(scratch, "core.err"), "w", encoding="utf-8"))
    socket = os.path.join(run_dir, f"{instance}.sock")
    deadline = time.monotonic() + 10
    while not os.path.exists(socket) and time.monotonic() < deadline:
        time.sleep(0.05)
    lcm = subprocess.Popen([os.path.join(build, "bridges", "lcm", "hapticctrl-lcm"), "--instance",
                            instance], env=env, stdin=subprocess.DEVNULL,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1)  # the bridge attached and publishing
    return [lcm, core]


def controller_said(scratch):
    """The end of the block's controller's stderr, when it had one."""
    path = os.path.join(scratch, "core.err")
    if not os.path.exists(path):
        return ""
    with open(path, encoding="utf-8") as f:
        return f"\n--- hapticctrl-core's stderr\n{f.read()[-2000:]}"


def run(block, build, scratch):
    text = block.text
    for old, new in block.replacements:
        if old not in text:
            return f"'{old}' is not in the block"
        text = text.replace(old, new.replace("{scratch}", scratch))
    env = dict(os.environ)
    processes = start_controller(build, scratch, env) if block.controller else []
    try:
        r = subprocess.run(["bash", "-euo", "pipefail", "-c", text], cwd=scratch, env=env,
                           stdin=subprocess.DEVNULL, capture_output=True, text=True,
                           timeout=BLOCK_TIMEOUT_S, check=False)
    except subprocess.TimeoutExpired:
        return f"did not end within {BLOCK_TIMEOUT_S} s"
    finally:
        for p in processes:
            p.send_signal(signal.SIGTERM)
            p.wait(timeout=10)
    if r.returncode != 0:
        return f"exit {r.returncode}\n--- stdout\n{r.stdout[-3000:]}\n--- stderr\n{r.stderr[-3000:]}"
    for pattern in block.expected:
        if not glob.glob(os.path.join(scratch, pattern)):
            return f"made no {pattern}\n--- stdout\n{r.stdout[-3000:]}{controller_said(scratch)}"
    return None


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 64
    source, build = (os.path.abspath(a) for a in sys.argv[1:3])
    listing = "--list" in sys.argv[3:]
    blocks, errors = [], []
    for path in documents(source):
        found, wrong = blocks_of(source, path)
        blocks += found
        errors += wrong
    for b in blocks:
        if b.kind == "manual":
            if not b.reason:
                errors.append(f"{b.where()}: a manual block needs its reason")
            print(f"manual  {b.where()}: {b.reason}")
    for b in (b for b in blocks if b.kind == "run"):
        if listing:
            print(f"run     {b.where()}")
            continue
        scratch = workspace(source, build)
        start = time.monotonic()
        try:
            failure = run(b, build, scratch)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        took = time.monotonic() - start
        print(f"run     {b.where()}: {'FAILED' if failure else 'ok'} ({took:.1f} s)")
        if failure:
            errors.append(f"{b.where()}: {failure}")
    for e in errors:
        print(f"check_docs: {e}", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Replays the hostile-input corpus (cases.py) against the real posemorph-bake
and posemorph-view processes, each under a 1 GiB address-space limit, 10 s of
CPU time and 60 s of wall-clock time, and asserts for every case: the expected exit status (1 for bad
input, 2 for usage, 0 where the limits admit the input), exactly one line on
stderr naming the offending file (or option) and the problem, nothing written
and no temporary left in the case's folder, an existing output untouched.

usage: replay.py --bake BIN --view BIN --work DIR [--only NAME] [--table]
Prints one line per case (status, CPU seconds, peak resident memory) and the
worst time and memory over the corpus. CPU time (user + system, all threads)
is the bound, not wall-clock time: it does not grow when other tests share the
machine, so the bound holds the tool's own work to account and not the load."""
import argparse
import os
import re
import resource
import shutil
import signal
import sys
import time

sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as corpus  # noqa: E402

ADDRESS_LIMIT = 1 << 30
CPU_LIMIT_S = 10.0   # the bound every case must stay within
WALL_LIMIT_S = 60.0  # a process that waits (not computing) is stopped here
TICKS = os.sysconf('SC_CLK_TCK')
PRLIMIT = shutil.which('prlimit') or '/usr/bin/prlimit'


def listing(folder):
    out = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            p = os.path.join(root, name)
            st = os.lstat(p)
            out[os.path.relpath(p, folder)] = (st.st_size, st.st_mtime_ns, st.st_mode)
    return out


def peak_resident_kib(pid):
    try:
        with open('/proc/%d/status' % pid) as f:
            for line in f:
                if line.startswith('VmHWM:'):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def cpu_seconds(pid):
    """User + system time of a running process, all its threads."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            fields = f.read().rsplit(')', 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / TICKS  # utime, stime (fields 14, 15)
    except (OSError, IndexError, ValueError):
        return 0.0


def run(argv, cwd, env):
    """Runs argv under prlimit (which sets the address-space limit and execs
    the tool in the same process); returns (exit status or None when stopped
    at a limit, CPU seconds, wall seconds, peak RSS in KiB, stdout, stderr)."""
    out_path, err_path = os.path.join(cwd, '..', '.stdout'), os.path.join(cwd, '..', '.stderr')
    with open(out_path, 'wb') as o, open(err_path, 'wb') as e, open(os.devnull, 'rb') as null:
        own_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        start = time.monotonic()
        pid = os.posix_spawn(PRLIMIT, [PRLIMIT, '--as=%d' % ADDRESS_LIMIT, '--'] + argv, env,
                             file_actions=[(os.POSIX_SPAWN_DUP2, null.fileno(), 0), (os.POSIX_SPAWN_DUP2, o.fileno(), 1),
                                           (os.POSIX_SPAWN_DUP2, e.fileno(), 2)], setsid=True)
        status, rss, cpu, stopped = None, 0, 0.0, False
        while True:
            # The tool's own peak (VmHWM of the process after exec), sampled
            # every 5 ms up to its exit; ru_maxrss would count this script too.
            rss = max(rss, peak_resident_kib(pid))
            cpu = max(cpu, cpu_seconds(pid))
            wpid, wstatus, usage = os.wait4(pid, os.WNOHANG)
            if wpid == pid:
                status = os.waitstatus_to_exitcode(wstatus)
                cpu = usage.ru_utime + usage.ru_stime
                # A peak above this script's own size is the tool's (fork copied ours).
                if usage.ru_maxrss > own_kib:
                    rss = max(rss, usage.ru_maxrss)
                break
            if (cpu > CPU_LIMIT_S or time.monotonic() - start > WALL_LIMIT_S) and not stopped:
                stopped = True
                os.killpg(pid, signal.SIGKILL)
            time.sleep(0.005)
        seconds = time.monotonic() - start
    with open(out_path, 'rb') as o, open(err_path, 'rb') as e:
        stdout, stderr = o.read(), e.read()
    os.remove(out_path)
    os.remove(err_path)
    return (None if stopped else status), cpu, seconds, rss, stdout, stderr


def check(case, tools, work, env):
    folder = os.path.join(work, case.name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    case.setup(folder)
    before = listing(folder)
    snapshot = {p: open(os.path.join(folder, p), 'rb').read()
                for p in before if os.path.isfile(os.path.join(folder, p)) and not os.path.islink(os.path.join(folder, p))
                and before[p][0] < (1 << 20)}
    argv = [tools[case.tool]] + [a.replace('{w}', folder) for a in case.args]
    status, cpu, seconds, rss, stdout, stderr = run(argv, folder, env)
    problems = []
    text = stderr.decode('utf-8', 'replace')
    if status is None:
        problems.append('stopped after %.2f s of CPU time, %.2f s in all (limits %g s CPU, %g s in all)' % (
            cpu, seconds, CPU_LIMIT_S, WALL_LIMIT_S))
    elif cpu > CPU_LIMIT_S:
        problems.append('took %.2f s of CPU time, more than %g s' % (cpu, CPU_LIMIT_S))
    elif status != case.status:
        problems.append('exit status %s, expected %d' % (status, case.status))
    after = listing(folder)
    allowed = set(case.writes)
    # A bake from drawings may write its atlas page beside the rig (one page for these drawings).
    maybe = {w[:-len('.pmrig')] + '.page0.png' for w in case.writes if w.endswith('.pmrig')}
    for p in sorted(set(after) - set(before)):
        if p not in allowed and p not in maybe:
            problems.append('left %s behind' % p)
    for p, data in snapshot.items():
        path = os.path.join(folder, p)
        if p not in allowed and (not os.path.exists(path) or open(path, 'rb').read() != data):
            problems.append('changed %s' % p)
    if case.status != 0:
        lines = text.splitlines()
        if case.one_line and (len(lines) != 1 or not text.endswith('\n')):
            problems.append('%d lines on stderr, expected one' % len(lines))
        names = [n.replace('{w}', folder) for n in case.names]
        for n in names:
            if n not in text:
                problems.append('the message does not name %s' % n)
        if not re.search(case.message, text):
            problems.append('the message does not match /%s/' % case.message)
    else:
        for p in case.writes:
            if not os.path.exists(os.path.join(folder, p)):
                problems.append('did not write %s' % p)
        if case.message and not re.search(case.message, stdout.decode('utf-8', 'replace') + text):
            problems.append('the output does not match /%s/' % case.message)
    if not problems:
        shutil.rmtree(folder, ignore_errors=True)
    return problems, status, cpu, seconds, rss, text.strip()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--bake', required=True)
    ap.add_argument('--view')
    ap.add_argument('--work', required=True)
    ap.add_argument('--only')
    args = ap.parse_args()
    tools = {'bake': os.path.abspath(args.bake), 'view': os.path.abspath(args.view) if args.view else None}
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = dict(os.environ)
    corpus.prepare(work, tools)
    failures, worst_s, worst_rss = 0, (0, ''), (0, '')
    selected = [c for c in corpus.CASES if not args.only or re.search(args.only, c.name)]
    for case in selected:
        if tools[case.tool] is None:
            print('skip  %-44s (no %s given)' % (case.name, case.tool))
            continue
        problems, status, cpu, seconds, rss, message = check(case, tools, work, env)
        worst_s = max(worst_s, (cpu, case.name))
        worst_rss = max(worst_rss, (rss, case.name))
        mark = 'ok  ' if not problems else 'FAIL'
        print('%s  %-44s exit %-4s %6.2f s CPU %6.2f s %8.1f MiB  %s' % (mark, case.name, status, cpu, seconds,
                                                                     rss / 1024.0, message[:160]))
        for p in problems:
            print('      - ' + p)
            failures += 1 if p is problems[0] else 0
    print('%d cases, %d failed; worst CPU time %.2f s (%s), worst peak memory %.1f MiB (%s)' % (
        len(selected), failures, worst_s[0], worst_s[1], worst_rss[0] / 1024.0, worst_rss[1]))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())

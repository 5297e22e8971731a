# SPDX-License-Identifier: MIT
"""Prints posemorph-bench's JSON output (medians) as docs/performance.md's tables."""
import json
import re
import sys


PATH_NAMES = {1: "scalar", 2: "sse2", 3: "avx2", 4: "avx512", 5: "neon", 6: "wasm-simd"}


def print_paths(median, data):
    """The kernel paths (BM_PathRatios, BM_PathFrame, BM_PathCrowd), when they ran."""
    ratios = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") == "median" and b["run_name"].startswith("BM_PathRatios/"):
            ratios[int(b["run_name"].split("/")[1])] = b
    if not ratios:
        return
    best = re.search(r"best=(\S+)", next(iter(ratios.values())).get("label", ""))
    best = best.group(1) if best else "?"
    print(f"\nKernel paths, forced on this CPU (1035-vertex, N = 8 plate; ratios to the {best} path "
          f"and to Eigen/CHOLMOD measured in back-to-back bursts, BM_PathRatios):\n")
    print("| path | frame | frame / " + best + " | crowd of 1000, 1 thread | 2 threads | crowd / " + best +
          " | solve / Eigen | solve / CHOLMOD |")
    print("|---|---|---|---|---|---|---|---|")
    for isa in sorted(ratios, key=lambda i: -i if i <= 4 else -i - 10):
        r = ratios[isa]
        frame = median.get(f"BM_PathFrame/{isa}")
        crowd1 = median.get(f"BM_PathCrowd/{isa}/1/real_time")
        crowd2 = median.get(f"BM_PathCrowd/{isa}/2/real_time")
        cell = lambda v, unit, scale: f"{v / scale:.1f} {unit}" if v is not None else "-"
        print(f"| {PATH_NAMES.get(isa, isa)} | {cell(frame, 'us', 1)} | {r['frame_vs_best']:.2f} | "
              f"{cell(crowd1, 'ms', 1e3)} | {cell(crowd2, 'ms', 1e3)} | {r['crowd_vs_best']:.2f} | "
              f"{r['solve_vs_eigen']:.2f} | {r['solve_vs_cholmod']:.2f} |")


def print_parts(median, label, data):
    """A layered character glued in one solve against its parts solved apart (parts_bench.cpp)."""
    if not any(n.startswith("BM_PartsFrame/") for n in median):
        return
    gaps = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") == "median" and b["run_name"].startswith("BM_PartsFrame/"):
            gaps[b["run_name"]] = b.get("joint_gap")
    print("\nLayered characters, their parts glued in one solve against the same parts baked as rigs of their "
          "own and solved one after the other: the body and arm of tests/runtime/rigs/make_arm.py at two "
          "densities (rig units, 4 px per unit), and Pell, the drawn layered sample (seven parts; rig units are "
          "drawing pixels), and Pell with a face channel (its body glued; the eyes and the mouth driven by "
          "their own channel, each solved on its own and placed on its joint; both channels moving). The joint "
          "gap is the largest distance between a joint's two copies (for an attachment, its joint and the "
          "body's point) over the frames timed:\n")
    print("| character | frame | crowd of 1000, 1 thread | joint gap |")
    print("|---|---|---|---|")
    for density in (0, 1, 2):
        for mode in (0, 1):
            key = f"/{density}/{mode}"
            frame, crowd = median.get("BM_PartsFrame" + key), median.get("BM_PartsCrowd1000" + key)
            if frame is None:
                continue
            gap = gaps.get("BM_PartsFrame" + key)
            crowd_cell = f"{crowd / 1e3:.2f} ms" if crowd is not None else "-"
            gap_cell = f"{gap:.3g}" if gap is not None else "-"
            print(f"| {label['BM_PartsFrame' + key]} | {frame:.{1 if frame >= 1 else 3}f} us | {crowd_cell} | {gap_cell} |")
    # Pell with a face channel: the body glued, the eyes and the mouth
    # attachments of their own channel (AttachJob).
    frame, crowd = median.get("BM_ChannelsFrame"), median.get("BM_ChannelsCrowd1000")
    if frame is not None:
        gap = next((b.get("joint_gap") for b in data["benchmarks"]
                    if b.get("aggregate_name") == "median" and b["run_name"] == "BM_ChannelsFrame"), None)
        crowd_cell = f"{crowd / 1e3:.2f} ms" if crowd is not None else "-"
        gap_cell = f"{gap:.3g}" if gap is not None else "-"
        print(f"| {label['BM_ChannelsFrame']} | {frame:.1f} us | {crowd_cell} | {gap_cell} |")


def main(path, paths_only=False):
    with open(path) as f:
        data = json.load(f)
    median = {}
    label = {}
    paired = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        name = re.sub(r"/min_time:[0-9.]+", "", b["run_name"])
        if name.startswith("BM_PairedRatios/"):
            paired[name[len("BM_PairedRatios"):]] = b
        median[name] = b["real_time"] * {"ns": 1e-3, "us": 1, "ms": 1e3}[b["time_unit"]]  # microseconds
        label[name] = b.get("label", "")
    ctx = data["context"]
    print(f"{ctx.get('num_cpus')} x {ctx.get('mhz_per_cpu')} MHz, {ctx.get('date')}; medians of "
          f"{data['benchmarks'][0].get('repetitions', '?')} interleaved repetitions, microseconds\n")
    if paths_only:
        print_paths(median, data)
        return

    print("Times are medians; the last three columns are medians of ratios measured in back-to-back bursts (BM_PairedRatios).\n")
    print("| vertices | N | nnz(L) | frame | solve | Eigen solve | CHOLMOD solve | refactor+solve | solve/Eigen | solve/CHOLMOD | frame/Eigen solve |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for size in range(4):
        for poses in (4, 8):
            key = f"/{size}/{poses}"
            need = ["BM_RuntimeFrame", "BM_RuntimeSolve", "BM_EigenSolve", "BM_CholmodSolve", "BM_EigenRefactorEveryFrame"]
            if not all(n + key in median for n in need):
                continue
            frame, solve, eigen, cholmod, refactor = (median[n + key] for n in need)
            m = re.search(r"V=(\d+) N=(\d+) nnz\(L\)=(\d+)", label["BM_RuntimeSolve" + key])
            p = paired.get(key)
            ratios = (f"{p['solve_vs_eigen']:.2f} | {p['solve_vs_cholmod']:.2f} | {p['frame_vs_eigen_solve']:.2f}" if p else
                      f"{solve / eigen:.2f} | {solve / cholmod:.2f} | {frame / eigen:.2f}")
            print(f"| {m.group(1)} | {m.group(2)} | {m.group(3)} | {frame:.1f} | {solve:.1f} | {eigen:.1f} | {cholmod:.1f} | "
                  f"{refactor:.0f} | {ratios} |")

    print("\nCrowds of one rig (the 1035-vertex, N = 8 plate), weights + batched morph per frame:\n")
    print("| characters | threads | frame | per character |")
    print("|---|---|---|---|")
    for name in sorted((n for n in median if n.startswith("BM_Crowd/")),
                       key=lambda n: tuple(int(x) for x in n.split("/")[1:3])):
        count, threads = (int(x) for x in name.split("/")[1:3])
        t = median[name]
        print(f"| {count} | {threads} | {t:.0f} us | {t / count:.1f} us |")

    print_parts(median, label, data)
    print_paths(median, data)

    print("\nSamples (single character):\n")
    print("| benchmark | median |")
    print("|---|---|")
    names = {"0": "snake", "1": "worm-line", "2": "strip-1000",  # then the same rigs, compact
             "3": "snake compact", "4": "worm-line compact", "5": "strip-1000 compact"}
    for n in sorted(median):
        m = re.match(r"BM_(Frame|Weights|Solve|Load|Bake)/(\d)$", n)
        if m:
            print(f"| {m.group(1)} {names[m.group(2)]} ({label[n]}) | {median[n]:.{1 if median[n] >= 1 else 3}f} us |")
    for n in ("BM_DeformerSetup", "BM_DeformerDrag"):
        if n in median:
            print(f"| {n[3:]} gingerbread ({label[n]}) | {median[n]:.1f} us |")


if __name__ == "__main__":
    main(sys.argv[1], "--paths-only" in sys.argv[2:])

#!/usr/bin/python3
"""Draws the figures of `nephele bench` from its JSON (matplotlib, Agg backend, no display).

Usage: /usr/bin/python3 scripts/plot_bench.py BENCH_JSON OUT_DIR

Writes into OUT_DIR, replacing each file whole (a temporary file renamed over it):
- bench.png: the seed's study (seed 000, section 4), frames per second (log scale) against
  cloud density, coverage and resolution (megapixels), one line per march mode, from the
  JSON's "sweeps" (the rows of bench.csv);
- bench_frame_times.png: each real-time series' device time per frame against the frame's
  index, with its median and 99th percentile as horizontal lines, from "frame_times_ms"
  ({"static": [...], "moving": [...]}) and "<series>_p50_ms" / "<series>_p99_ms" (computed
  from the frames where absent).
A figure whose data the JSON lacks is left out without a word (a --realtime-only JSON has no
sweeps). Prints "wrote PATH" for each file. Exit status 3 when matplotlib cannot be imported
(`nephele bench` then says the plot was skipped), 2 for bad arguments or input.

`nephele bench` runs the copy of this file embedded in its binary, passed to
/usr/bin/python3 with -c: it uses nothing beside it (no __file__), so it runs from anywhere.
"""
import json
import os
import sys

EXIT_BAD_INPUT = 2
EXIT_NO_MATPLOTLIB = 3

# The sweeps of the seed's study: (sweep, title, x label, x of a row).
SWEEP_PANELS = [
    ("density", "FPS vs cloud density", "density", lambda row: row["density"]),
    ("coverage", "FPS vs coverage", "coverage", lambda row: row["coverage"]),
    ("resolution", "FPS vs resolution", "megapixels",
     lambda row: row["width"] * row["height"] * 1e-6),
]
MODES = ["default", "baseline"]  # march modes, in the order of the legend
STYLE = {"default": ("tab:blue", "o"), "baseline": ("tab:orange", "s")}


def save(figure, out_dir, name):
    """Saves the figure as OUT_DIR/name through a temporary file beside it."""
    path = os.path.join(out_dir, name)
    temporary = os.path.join(out_dir, ".%s.tmp%d.png" % (os.path.splitext(name)[0], os.getpid()))
    try:
        figure.savefig(temporary, dpi=100)
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)
    print("wrote " + path)


def plot_sweeps(plt, sweeps, out_dir):
    """bench.png: frames per second over each sweep, both march modes."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    figure, axes = plt.subplots(1, len(SWEEP_PANELS), figsize=(19.2, 4.4))
    for ax, (sweep, title, x_label, x_of) in zip(axes, SWEEP_PANELS):
        for mode in MODES + sorted({r["mode"] for r in sweeps} - set(MODES)):
            rows = [r for r in sweeps if r["sweep"] == sweep and r["mode"] == mode]
            if not rows:
                continue
            color, marker = STYLE.get(mode, (None, "^"))
            ax.plot([x_of(r) for r in rows], [r["fps"] for r in rows], marker=marker,
                    color=color, label=mode)
        ax.set_yscale("log")
        # Ticks at 1, 2 and 5 times the powers of ten, written plainly (0.5, 2, 10).
        ax.yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: "%g" % value))
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_title(title)
        ax.set_xlabel(x_label)
        ax.set_ylabel("frames per second")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    figure.tight_layout()
    save(figure, out_dir, "bench.png")
    plt.close(figure)


def percentile(values, p):
    """The p-th percentile, interpolated linearly between the sorted values."""
    ordered = sorted(values)
    at = (len(ordered) - 1) * p / 100.0
    below = int(at)
    above = min(below + 1, len(ordered) - 1)
    return ordered[below] + (ordered[above] - ordered[below]) * (at - below)


def plot_frame_times(plt, data, out_dir):
    """bench_frame_times.png: device time per frame, one line per series."""
    figure, ax = plt.subplots(figsize=(12.8, 4.8))
    for index, (series, times) in enumerate(data["frame_times_ms"].items()):
        if not times:
            continue
        color = "C%d" % index
        ax.plot(range(len(times)), times, color=color, linewidth=1.2, label=series)
        median = data.get(series + "_p50_ms", percentile(times, 50))
        p99 = data.get(series + "_p99_ms", percentile(times, 99))
        ax.axhline(median, color=color, linestyle="--", linewidth=1,
                   label="%s median %.1f ms" % (series, median))
        ax.axhline(p99, color=color, linestyle=":", linewidth=1,
                   label="%s p99 %.1f ms" % (series, p99))
    title = "Frame times"
    if "width" in data and "height" in data:
        title += ", %dx%d" % (data["width"], data["height"])
    if data.get("device"):
        title += " on " + data["device"]
    ax.set_title(title)
    ax.set_xlabel("frame")
    ax.set_ylabel("device time (ms)")
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    figure.tight_layout()
    save(figure, out_dir, "bench_frame_times.png")
    plt.close(figure)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_bench.py BENCH_JSON OUT_DIR\n")
        return EXIT_BAD_INPUT
    json_path, out_dir = argv[1], argv[2]
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        sys.stderr.write("cannot import matplotlib: %s\n" % error)
        return EXIT_NO_MATPLOTLIB
    try:
        with open(json_path, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as error:
        sys.stderr.write("%s: %s\n" % (json_path, error))
        return EXIT_BAD_INPUT
    if not os.path.isdir(out_dir):
        sys.stderr.write("%s: not a directory\n" % out_dir)
        return EXIT_BAD_INPUT
    if data.get("sweeps"):
        plot_sweeps(plt, data["sweeps"], out_dir)
    if data.get("frame_times_ms"):
        plot_frame_times(plt, data, out_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

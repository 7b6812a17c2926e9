#!/usr/bin/python3
"""The cost of Python in the loop (docs/BENCHMARKS.md, "Python in the loop"): the small
scenario's playback run 0 in partial maps, driven by retrace's own stack, (a) stepped from Python
through retrace.Episode (observe() hands out every odometry reading and scan as NumPy arrays,
act() answers) and (b) as `retrace run` plays it back in C++. Each is timed by the CPU time of the
thread that runs the episode: (a) the process's CPU time over the stepping loop (one thread), (b)
the run's own cpu.cpu_time_s. Prints the real-time factor (simulated s per CPU s) of each repeat,
the medians and their ratio.

    PYTHONPATH=build/python /usr/bin/python3 scripts/python_step_benchmark.py [--repeats 5]
"""

import argparse
import pathlib
import statistics
import tempfile
import time

import retrace

SMALL = pathlib.Path(__file__).resolve().parents[1] / "scenarios" / "small.yaml"


def stepped_from_python(teaching):
    episode = teaching.episode(0, builtin=True)
    start = time.process_time()
    while not episode.done:
        observation = episode.observe()
        episode.act()
    return observation.time / (time.process_time() - start)


def run_in_cpp(out):
    result = retrace.run(SMALL, modes="partial", repeats=1, jobs=1, figures=False, report=False,
                         out=out, progress=False)
    run = retrace.load_results(result.out).modes["partial"].metrics["runs"][0]
    return run["cpu"]["sim_time_s"] / run["cpu"]["cpu_time_s"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    teaching = retrace.Teaching(SMALL, mode="partial", progress=False)
    python, cpp = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.repeats):
            python.append(stepped_from_python(teaching))
            cpp.append(run_in_cpp(pathlib.Path(tmp) / str(i)))
            print(f"repeat {i + 1}: stepped from Python {python[-1]:.0f}x, C++ {cpp[-1]:.0f}x "
                  "real time", flush=True)
    a, b = statistics.median(python), statistics.median(cpp)
    print(f"median real-time factor: stepped from Python {a:.0f}x, C++ {b:.0f}x; "
          f"Python / C++ = {a / b:.2f}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Benchmark figures as ratios to a yardstick timed in the same run, and the
check of a run's ratios against a recorded run's (scripts/bench.sh --check,
--record; docs/benchmarks.md, The speed check).

The yardstick is FCL's exhaustive contact query on Table 1 #4: step_bench
times it itself and prints every step figure over its median (the counter
p99_per_fcl4); contact_bench times it as Table1/case4/fcl_contacts, and each
query's time is divided by it here. A ratio moves with the code, not with how
fast or busy the machine is.

Usage:
  bench_ratios.py record STEP_JSON CONTACT_JSON --commit SHA --command CMD --out DIR
      Writes DIR/<date>.json from the two benchmarks' JSON output (Google
      Benchmark's --benchmark_out) and prints its path; refuses (exit 1) a
      run whose two yardsticks differ by more than 10 %.
  bench_ratios.py compare BASELINE CURRENT [CURRENT ...] [--tolerance 0.2]
      BASELINE is a record or a directory of them: the newest made on the
      current run's CPU model is read (ratios to the yardstick differ between
      CPU kinds), else the newest, said so.
      Exit 1, naming each, when a benchmark's ratio grew by more than the
      tolerance; benchmarks in only one of the two are listed, not judged.
      Given several current runs, each benchmark's lowest ratio among them
      is judged: slower code is slower in every run, a busy machine in some.
"""

import argparse
import datetime
import json
import os
import shutil
import statistics
import subprocess
import sys

# contact_bench's yardstick, and the counters step_bench prints per step.
CONTACT_YARDSTICK = "Table1/case4/fcl_contacts"
STEP_YARDSTICK = "Yardstick/fcl_contacts_case4"
STEP_FIGURE = "p99"  # the step figure that is checked
CONTACT_PREFIXES = ("Table1/", "Coherent/")
# How far apart the two benchmarks' yardsticks may be in a record.
YARDSTICK_SPREAD = 0.1

_MICROS_PER_UNIT = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def medians(run):
    """Each benchmark's entries by name: its median aggregate when the run
    had repetitions, else the median of its iterations, field by field."""
    by_name = {}
    for entry in run.get("benchmarks", []):
        if entry.get("error_occurred"):
            continue
        name = entry.get("run_name", entry["name"])
        if entry.get("run_type") == "aggregate":
            if entry.get("aggregate_name") == "median":
                by_name.setdefault(name, {})["median"] = entry
        else:
            by_name.setdefault(name, {}).setdefault("iterations", []).append(entry)
    out = {}
    for name, found in by_name.items():
        if "median" in found:
            out[name] = found["median"]
            continue
        entries = found["iterations"]
        merged = dict(entries[0])
        for key, value in entries[0].items():
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                merged[key] = statistics.median(e[key] for e in entries)
        out[name] = merged
    return out


def cpu_us(entry):
    return entry["cpu_time"] * _MICROS_PER_UNIT[entry.get("time_unit", "ns")]


def step_ratios(run):
    """step_bench's steps: the checked figure in microseconds and over the
    yardstick; and the yardstick's median, microseconds (None if absent)."""
    figures = {}
    yardstick_us = None
    for name, entry in medians(run).items():
        if name == STEP_YARDSTICK:
            yardstick_us = entry["median_us"]
        elif name.startswith("Step/"):
            figures[name] = {"ratio": entry[STEP_FIGURE + "_per_fcl4"],
                             "us": entry[STEP_FIGURE + "_us"]}
    return figures, yardstick_us


def contact_ratios(run):
    """contact_bench's queries: CPU time per call in microseconds and over
    the yardstick's; and the yardstick's, microseconds. Empty without it."""
    by_name = medians(run)
    if CONTACT_YARDSTICK not in by_name:
        return {}, None
    yardstick_us = cpu_us(by_name[CONTACT_YARDSTICK])
    figures = {}
    for name, entry in by_name.items():
        if name != CONTACT_YARDSTICK and name.startswith(CONTACT_PREFIXES):
            us = cpu_us(entry)
            figures[name] = {"ratio": us / yardstick_us, "us": us}
    return figures, yardstick_us


def cpu_model():
    """The CPU's model name as lscpu gives it, or "" without lscpu."""
    if not shutil.which("lscpu"):
        return ""
    out = subprocess.run(["lscpu"], capture_output=True, text=True, check=False).stdout
    for line in out.splitlines():
        if line.startswith("Model name:"):
            return line.split(":", 1)[1].strip()
    return ""


def machine(context, cpu):
    """The machine as its benchmark context and the system describe it
    (`cpu`: its CPU model, cpu_model())."""
    parts = [f"{context.get('num_cpus', '?')} cores"]
    if cpu:
        parts.append(cpu)
    if "mhz_per_cpu" in context:
        parts.append(f"{context['mhz_per_cpu']} MHz")
    try:
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
        parts.append(f"{memory / 2**30:.0f} GiB")
    except (ValueError, OSError):
        pass
    return ", ".join(parts)


def cpu_of(record):
    """A record's CPU model: its "cpu", or for a record made before it had
    one, the part of its "machine" that is not cores, MHz or GiB."""
    if "cpu" in record:
        return record["cpu"]
    for part in record.get("machine", "").split(", "):
        if not part.endswith((" cores", " MHz", " GiB")):
            return part
    return ""


def make_record(step_run, contact_run, commit, command):
    step, step_yardstick = step_ratios(step_run)
    contact, contact_yardstick = contact_ratios(contact_run)
    context = step_run.get("context", {})
    date = datetime.datetime.fromisoformat(context["date"]).astimezone(datetime.timezone.utc)
    cpu = cpu_model()
    return {
        "date": date.strftime("%Y-%m-%dT%H:%M:%SZ"),
        "commit": commit,
        "machine": machine(context, cpu),
        "cpu": cpu,
        "command": command,
        "load_avg": {"step_bench": context.get("load_avg"),
                     "contact_bench": contact_run.get("context", {}).get("load_avg")},
        "yardstick_us": {"step_bench": step_yardstick, "contact_bench": contact_yardstick},
        "benchmarks": dict(sorted({**step, **contact}.items())),
    }


def newest_record(path, cpu):
    """`path` itself, or of the records in directory `path` the newest made
    on CPU model `cpu` (ratios to the yardstick differ between CPU kinds),
    else the newest of all: its path, the record, and whether it is from
    that CPU."""
    if not os.path.isdir(path):
        record = load_json(path)
        return path, record, cpu_of(record) == cpu
    records = {os.path.join(path, f): load_json(os.path.join(path, f))
               for f in os.listdir(path) if f.endswith(".json")}
    if not records:
        sys.exit(f"no record (*.json) in {path}: scripts/bench.sh --record writes one")
    same_cpu = [p for p, rec in records.items() if cpu and cpu_of(rec) == cpu]
    newest = max(same_cpu or records, key=lambda p: (records[p]["date"], p))
    return newest, records[newest], bool(same_cpu)


def compare(baseline, current, tolerance):
    """Lines to print and the names of the benchmarks whose ratio grew by
    more than `tolerance` (a fraction)."""
    lines, slower = [], []
    base, now = baseline["benchmarks"], current["benchmarks"]
    for name in sorted(base.keys() | now.keys()):
        if name not in now:
            lines.append(f"  not run:  {name}")
            continue
        if name not in base:
            lines.append(f"  not in the record: {name}")
            continue
        before, after = base[name]["ratio"], now[name]["ratio"]
        change = after / before - 1
        verdict = "ok"
        if change > tolerance:
            verdict = "SLOWER"
            slower.append(name)
        lines.append(f"  {verdict:6} {change * 100:+6.1f} %  {name}: {after:.4g} x yardstick "
                     f"({now[name]['us']:.4g} us), recorded {before:.4g}")
    return lines, slower


def lowest_ratios(runs):
    """One run from several (records of the same benchmarks): each
    benchmark's entry from the run where its ratio was lowest."""
    merged = dict(runs[0])
    benchmarks = {}
    for run in runs:
        for name, entry in run["benchmarks"].items():
            if name not in benchmarks or entry["ratio"] < benchmarks[name]["ratio"]:
                benchmarks[name] = entry
    merged["benchmarks"] = benchmarks
    return merged


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command_name", required=True)
    record = sub.add_parser("record")
    record.add_argument("step_json")
    record.add_argument("contact_json")
    record.add_argument("--commit", required=True)
    record.add_argument("--command", required=True)
    record.add_argument("--out", required=True, help="directory of records")
    check = sub.add_parser("compare")
    check.add_argument("baseline", help="a record, or a directory: its newest record")
    check.add_argument("current", nargs="+", help="one run's record, or several")
    check.add_argument("--tolerance", type=float, default=0.2)
    args = parser.parse_args(argv)

    if args.command_name == "record":
        rec = make_record(load_json(args.step_json), load_json(args.contact_json), args.commit,
                          args.command)
        yardsticks = rec["yardstick_us"]
        spread = yardsticks["step_bench"] / yardsticks["contact_bench"] - 1
        if abs(spread) > YARDSTICK_SPREAD:
            # The same query, timed by each benchmark: the machine's speed
            # changed between them, and every ratio of one would be off.
            print(f"no record: the yardstick took {yardsticks['step_bench']:.0f} us in "
                  f"step_bench and {yardsticks['contact_bench']:.0f} us in contact_bench "
                  f"({spread * 100:+.0f} %, more than {YARDSTICK_SPREAD * 100:.0f} %): the "
                  f"machine's speed changed during the run; make it again", file=sys.stderr)
            return 1
        os.makedirs(args.out, exist_ok=True)
        path = os.path.join(args.out, rec["date"].replace(":", "")[:-3] + "Z.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(rec, f, indent=2)
            f.write("\n")
        print(path)
        return 0

    current = lowest_ratios([load_json(path) for path in args.current])
    baseline_path, baseline, same_cpu = newest_record(args.baseline, cpu_of(current))
    if not same_cpu:
        print(f"No record from this CPU ({cpu_of(current) or 'unknown'}): against one from "
              f"{cpu_of(baseline) or 'an unknown CPU'}, whose ratios may differ by more than "
              f"the tolerance; scripts/bench.sh --record makes one here.")
    print(f"Ratios to the yardstick (FCL's contact query on Table 1 #4) against "
          f"{baseline_path} ({baseline['date']}, {baseline['commit']}); "
          f"fails above +{args.tolerance * 100:.0f} %"
          + (f" (each the lowest of {len(args.current)} runs)" if len(args.current) > 1 else "")
          + ":")
    lines, slower = compare(baseline, current, args.tolerance)
    print("\n".join(lines))
    if slower:
        print(f"FAILED: {len(slower)} slower by more than {args.tolerance * 100:.0f} %: "
              + ", ".join(slower))
        return 1
    print("passed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

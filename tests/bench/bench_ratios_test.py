#!/usr/bin/env python3
"""bench_ratios.py: the speed check's verdicts and the ratios it records.

Usage: bench_ratios_test.py [unittest args]

Feeds the script small files from testdata/: a record, a run within 20 %
of it and one beyond; and benchmark output in Google Benchmark's JSON.
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "bench_ratios.py")
DATA = os.path.join(HERE, "testdata")


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                          check=False)


def data(name):
    return os.path.join(DATA, name)


class CompareTest(unittest.TestCase):
    def test_within_tolerance_passes(self):
        # Ratios 16 % up and 12 % down pass, though the microseconds grew 39 %.
        result = run("compare", data("record.json"), data("within.json"))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("passed", result.stdout)
        self.assertNotIn("SLOWER", result.stdout)

    def test_beyond_tolerance_fails_naming_each(self):
        # Ratios 24 % and 25 % up fail, both named, though the microseconds fell.
        result = run("compare", data("record.json"), data("beyond.json"))
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        failed = [line for line in result.stdout.splitlines() if line.startswith("FAILED")]
        self.assertEqual(len(failed), 1, result.stdout)
        self.assertIn("Step/linked_rings/all_effects/threads:1", failed[0])
        self.assertIn("Table1/case4/sweep3d", failed[0])

    def test_of_several_runs_each_benchmarks_lowest_ratio_is_judged(self):
        # A run beyond the tolerance and one within it (the machine was busy
        # during the first): each benchmark is as fast as its better run, so
        # the check passes, and says how many runs it took the lowest of.
        result = run("compare", data("record.json"), data("beyond.json"), data("within.json"))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("each the lowest of 2 runs", result.stdout)
        self.assertNotIn("SLOWER", result.stdout)
        # Slower in both runs: it fails, naming each, as for one run.
        result = run("compare", data("record.json"), data("beyond.json"), data("beyond.json"))
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("Table1/case4/sweep3d", result.stdout.splitlines()[-1])

    def test_tolerance_is_an_argument(self):
        # The beyond run's largest growth is 25 %: a 30 % tolerance passes it.
        result = run("compare", data("record.json"), data("beyond.json"), "--tolerance", "0.3")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)

    def test_directory_reads_its_newest_record(self):
        # Of two records, the later date is the baseline, whatever the file names.
        with open(data("record.json"), encoding="utf-8") as f:
            old = json.load(f)
        new = json.loads(json.dumps(old))
        new["date"] = "2026-11-29T00:00:00Z"
        for figure in new["benchmarks"].values():
            figure["ratio"] *= 2  # against it, beyond.json is faster
        with tempfile.TemporaryDirectory() as records:
            for name, rec in (("b.json", old), ("a.json", new)):
                with open(os.path.join(records, name), "w", encoding="utf-8") as f:
                    json.dump(rec, f)
            result = run("compare", records, data("beyond.json"))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("a.json", result.stdout)

    def compare_in_records(self, cpus, current_cpu):
        """compare() of beyond.json, as run on `current_cpu`, with a directory
        of two records: b.json (record.json, which it is beyond) on cpus[0]
        and the later a.json (every ratio doubled: within) on cpus[1]."""
        with open(data("record.json"), encoding="utf-8") as f:
            old = json.load(f)
        new = json.loads(json.dumps(old))
        new["date"] = "2026-11-29T00:00:00Z"
        for figure in new["benchmarks"].values():
            figure["ratio"] *= 2
        old["cpu"], new["cpu"] = cpus
        with open(data("beyond.json"), encoding="utf-8") as f:
            current = json.load(f)
        current["cpu"] = current_cpu
        with tempfile.TemporaryDirectory() as records:
            for name, rec in (("b.json", old), ("a.json", new), ("current", current)):
                with open(os.path.join(records, name), "w", encoding="utf-8") as f:
                    json.dump(rec, f)
            return run("compare", records, os.path.join(records, "current"))

    def test_directory_reads_the_newest_record_from_the_runs_cpu(self):
        # The older record is from the run's CPU: it is the baseline, and fails the run.
        result = self.compare_in_records(("CPU A", "CPU B"), "CPU A")
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("b.json", result.stdout)
        self.assertNotIn("No record from this CPU", result.stdout)

    def test_without_a_record_from_the_runs_cpu_the_newest_is_read_and_said(self):
        result = self.compare_in_records(("CPU A", "CPU B"), "CPU C")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("a.json", result.stdout)
        self.assertIn("No record from this CPU (CPU C): against one from CPU B", result.stdout)

    def test_a_record_without_cpu_takes_it_from_its_machine(self):
        # Records made before "cpu" say it within "machine" only.
        with open(data("record.json"), encoding="utf-8") as f:
            old = json.load(f)
        old["machine"] = "2 cores, Intel(R) Xeon(R) Processor, 2600 MHz, 24 GiB"
        with open(data("beyond.json"), encoding="utf-8") as f:
            current = json.load(f)
        current["cpu"] = "Intel(R) Xeon(R) Processor"
        with tempfile.TemporaryDirectory() as records:
            for name, rec in (("old.json", old), ("current", current)):
                with open(os.path.join(records, name), "w", encoding="utf-8") as f:
                    json.dump(rec, f)
            result = run("compare", records, os.path.join(records, "current"))
        self.assertNotIn("No record from this CPU", result.stdout)
        self.assertIn("old.json", result.stdout)

    def test_benchmarks_in_one_file_only_are_listed_not_judged(self):
        # A benchmark the run left out and one the record lacks do not fail.
        with open(data("within.json"), encoding="utf-8") as f:
            current = json.load(f)
        current["benchmarks"]["Table1/case3/sweep3d"] = current["benchmarks"].pop(
            "Table1/case4/sweep3d")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "current.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(current, f)
            result = run("compare", data("record.json"), path)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("not run:  Table1/case4/sweep3d", result.stdout)
        self.assertIn("not in the record: Table1/case3/sweep3d", result.stdout)


class RecordTest(unittest.TestCase):
    def record(self):
        with tempfile.TemporaryDirectory() as out:
            result = run("record", data("step_run.json"), data("contact_run.json"), "--commit",
                         "abc1234", "--command", "scripts/bench.sh --record", "--out", out)
            self.assertEqual(result.returncode, 0, result.stderr)
            path = result.stdout.strip()
            self.assertEqual(os.path.dirname(path), out)
            with open(path, encoding="utf-8") as f:
                return os.path.basename(path), json.load(f)

    def test_says_the_cpu_within_the_machine_and_alone(self):
        _, rec = self.record()
        self.assertIsInstance(rec["cpu"], str)
        if rec["cpu"]:
            self.assertIn(f", {rec['cpu']}", rec["machine"])

    def test_named_by_the_step_run_date_in_utc(self):
        # 15:04:05+01:00 is 14:04:05Z.
        name, rec = self.record()
        self.assertEqual(name, "2026-11-27T1404Z.json")
        self.assertEqual(rec["date"], "2026-11-27T14:04:05Z")
        self.assertEqual(rec["commit"], "abc1234")

    def test_step_ratio_is_the_median_of_the_repetitions(self):
        # Three repetitions without aggregates: the medians 600 us and 0.3.
        _, rec = self.record()
        step = rec["benchmarks"]["Step/linked_rings/all_effects/threads:1"]
        self.assertEqual(step, {"ratio": 0.3, "us": 600.0})
        self.assertEqual(rec["yardstick_us"]["step_bench"], 2000.0)
        self.assertNotIn("Step/fine_organ/all_effects/threads:1", rec["benchmarks"])

    def test_contact_ratio_is_cpu_time_over_the_yardstick_median(self):
        # 600 us over 2,000 us; 0.48 ms over 2,000 us; the yardstick itself left out.
        _, rec = self.record()
        self.assertAlmostEqual(rec["benchmarks"]["Table1/case4/sweep3d"]["ratio"], 0.3)
        self.assertAlmostEqual(rec["benchmarks"]["Coherent/case4/sweep3d"]["ratio"], 0.24)
        self.assertAlmostEqual(rec["benchmarks"]["Coherent/case4/sweep3d"]["us"], 480.0)
        self.assertNotIn("Table1/case4/fcl_contacts", rec["benchmarks"])
        self.assertEqual(rec["yardstick_us"]["contact_bench"], 2000.0)

    def test_refuses_a_run_whose_two_yardsticks_differ_by_more_than_a_tenth(self):
        # The contact run's yardstick at 2,300 us against the step run's 2,000.
        with open(data("contact_run.json"), encoding="utf-8") as f:
            contact = json.load(f)
        contact["benchmarks"][0]["cpu_time"] = 2300
        with tempfile.TemporaryDirectory() as out:
            path = os.path.join(out, "contact.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(contact, f)
            result = run("record", data("step_run.json"), path, "--commit", "abc1234",
                         "--command", "scripts/bench.sh --record", "--out", out)
            self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
            self.assertIn("2000 us in step_bench and 2300 us in contact_bench", result.stderr)
            self.assertEqual(sorted(os.listdir(out)), ["contact.json"])


if __name__ == "__main__":
    unittest.main()

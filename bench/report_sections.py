"""The sections of docs/performance.md that each benchmark beyond the solver and node levels
adds (overhead, idle core, DP capability, consequence analysis, settling, in-process simulation,
Level 3), from one run's JSON; :mod:`report` puts them together."""

from __future__ import annotations

NOT_IN_THIS_RUN = "not in this run (the next `make bench` measures it)"


def _fmt(value: float | None, digits: int = 1) -> str:
    if value is None:
        return "-"
    if value != 0.0 and (abs(value) < 10 ** -digits or abs(value) >= 1e6):
        return f"{value:.1e}"
    return f"{value:.{digits}f}"


def _overhead_section(overhead: dict) -> list[str]:
    """The node's own cost against a bare rclpy node of the same rate (bench/overhead.py)."""
    lines = ["## The node's own cost against a bare rclpy node", "",
             f"`bench/overhead.py`: every node in a process of its own, driven over Fast DDS on loopback; "
             f"{overhead['seconds']:g} s per case after a warm-up, {overhead['rounds']} rounds alternating the nodes "
             "of a rate, medians over the rounds. Input: a WrenchStamped at each rate, answered by a bare node that "
             "publishes it back at once (`bench/bare.py echo`) and by `allocator_node` with `trigger: input`, "
             "`wrench_type: wrench_stamped` (its ThrusterCommands, with AllocationStatus published every sample; in "
             "the rows marked `status 50 Hz`, `status_rate_hz: 50`). "
             "Timer: `allocator_node` with `trigger: timer` against a bare node with one timer publishing one "
             "message. CPU per sample is utime + stime from /proc over the window per answer (per tick for "
             "timers); \"x\" is the ratio to the bare node of the same rate in the same run (target <= "
             f"{overhead['target_ratio']:g}). The last column is `allocate`'s wall time in the node "
             "(AllocationStatus.solve_time) against the process's CPU per sample: the same call takes several "
             "times its solver-bench median there, where the core idles between samples. \"Beyond allocate x\" "
             "is the CPU per sample less `allocate`'s mean wall time in the window, against the bare node's CPU "
             "per sample: what the node spends on everything but the maths.", "",
             "| case | node | rate Hz | CPU per sample ms | share of a core | publish to answer p50 / p99 ms | "
             "CPU x | p50 x | allocate in the node p50 ms (share of CPU per sample) | beyond allocate x |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for row in overhead["rows"]:
        latency = ("" if row["latency_ms_p50"] is None
                   else f"{_fmt(row['latency_ms_p50'], 3)} / {_fmt(row['latency_ms_p99'], 3)}")
        lines.append(f"| {row['kind']} | {row['node']} | {row['rate_hz']:g} | {_fmt(row['cpu_ms_per_sample'], 3)} | "
                     f"{row['cpu_percent']:.1f} % | {latency} | {row['cpu_ratio']:.2f} | "
                     f"{_fmt(row.get('latency_ratio'), 2)} | {_allocate_share(row)} | "
                     f"{_fmt(row.get('beyond_allocate_ratio'), 2)} |")
    return lines


def _idle_core_section(idle: dict) -> list[str]:
    """``allocate``'s CPU per sample after the core idles (bench/idle_core.py)."""
    lines = ["## `allocate` on an idle core", "",
             f"`bench/idle_core.py`: `allocate` in a plain loop, no ROS, {idle['samples']} samples of the node-cost "
             f"probe's turning request at {idle['rate_hz']:g} Hz per case, timed by the thread's CPU clock: back to "
             "back, and after the thread sleeps the gap before every sample (2 ms: a 500 Hz node's idle time, "
             f"10 ms: a 100 Hz node's); medians over {idle['rounds']} rounds. \"x\" is the multiple of the "
             "back-to-back figure. The same work costs that much more CPU when the core has idled, which is "
             "why `allocate` takes several times its solver-bench median inside the node (the table above).", "",
             "| vehicle | idle before each sample ms | CPU per sample p50 us | mean us | p50 x | mean x |",
             "|---|---|---|---|---|---|"]
    for vehicle, rows in idle["vehicles"].items():
        for row in rows:
            lines.append(f"| {vehicle} | {row['gap_ms']:g} | {_fmt(row['cpu_us_p50'], 1)} | "
                         f"{_fmt(row['cpu_us_mean'], 1)} | {row['p50_multiple']:.2f} | {row['mean_multiple']:.2f} |")
    return lines


def _dp_capability_section(run: dict) -> list[str]:
    """The wall and user CPU time of a full DNV-ST-0111 Level 1 run (bench/dp_capability.py)."""
    met = "yes" if run["wall_s_median"] < run["target_s"] else "no"
    return ["## DP capability Level 1", "",
            f"`bench/dp_capability.py`: a full Level 1 run on {run['vessel']} ({run['headings']} headings every "
            f"{run['heading_step_deg']:g} deg, {run['cases']} cases: intact and every redundancy group; a fresh "
            "analysis, nothing cached), timed by the wall clock and by the user CPU time of the process; the "
            f"medians over {run['repeats']} runs. A balance is one condition, heading and case; per balance, the "
            "wall time of a run over its balances.", "",
            "| vessel | summary | balances | wall s (median) | user CPU s (median) | per balance ms | target s | met |",
            "|---|---|---|---|---|---|---|---|",
            f"| {run['vessel']} | {run['summary']} | {run['balances']} | {run['wall_s_median']:.2f} | "
            f"{run['user_cpu_s_median']:.2f} | {1e3 * run['wall_s_median'] / run['balances']:.2f} | "
            f"< {run['target_s']:g} | {met} |"]


def _consequence_section(run: dict) -> list[str]:
    """The node's sample time with the online consequence analysis off and on (bench/consequence.py)."""
    off, analysis = run["sample_us_off"], run["analysis_ms"]
    lines = ["## Consequence analysis", "",
             f"`bench/consequence.py`: `allocator_node` on dp_vessel (two redundancy groups) at "
             f"{run['node_rate_hz']:g} Hz, its sample (allocate and publish) timed by the wall clock around it, "
             "GIL waits included, with the analysis off (`consequence.rate` 0) and at each rate, under a wrench "
             "that turns through loads that a group's loss could not hold and loads it could; "
             f"{run['seconds']:g} s per case over {run.get('rounds', 1)} rounds that alternate the cases. One "
             f"analysis (both groups) outside the node: median {analysis['median']:.2f} ms, p99 "
             f"{analysis['p99']:.2f} ms. At 1 Hz an analysis overlaps at most one or two of the node's samples "
             "a second, too few to move a median: a median's ratio away from 1 there is the shared machine's "
             "variation between rounds.", "",
             "| analysis | samples | median us | p99 us | max us | median / off | p99 / off | analyses published |",
             "|---|---|---|---|---|---|---|---|",
             f"| off | {off['samples']} | {off['median']:.0f} | {off['p99']:.0f} | {off['max']:.0f} | 1 | 1 | 0 |"]
    for on in run["on"]:
        times, ratio = on["sample_us"], on["ratio_to_off"]
        lines.append(f"| {on['consequence_rate_hz']:g} Hz | {times['samples']} | {times['median']:.0f} | "
                     f"{times['p99']:.0f} | {times['max']:.0f} | {ratio['median']:.2f} | {ratio['p99']:.2f} | "
                     f"{on['analyses_published']} |")
    return lines


def _allocate_share(row: dict) -> str:
    """``allocate``'s p50 wall time in the node and its share of the CPU per sample (none for a bare node)."""
    if row.get("allocate_ms_p50") is None:
        return ""
    return f"{_fmt(row['allocate_ms_p50'], 3)} ({100 * row['allocate_share']:.0f} %)"


def _settling_section(result: dict, off_grid: dict | None = None) -> list[str]:
    lines = ["## Rotatable thrusters near their capability", "",
             "`bench/settling.py --full`: a constant request held from rest for {samples} samples and judged over "
             "the last {judged}, in every direction of the surge/sway plane (every {step:g} deg) at {magnitudes} "
             "times the vessel's capability in that direction (an independent LP). \"Not at rest\": peak-to-peak "
             "angle change over {settled} deg, or a fallback, in the judged samples; \"deviation\": the largest "
             "per-DOF distance of the settled wrench from an independent optimum of the same static problem "
             "(SLSQP over every combination of convex pieces), as a fraction of the DOF's authority; "
             "\"violations\": samples that broke a rate, thrust or sector limit, checked by the sweep's own "
             "arithmetic. Times per sample over all samples of the sweep."]
    settling = result.get("settling")
    if settling is None:
        return [lines[0], "", f"{NOT_IN_THIS_RUN[0].upper()}{NOT_IN_THIS_RUN[1:]}."]
    directions, magnitudes = settling["directions_deg"], settling["magnitudes"]
    lines[2] = lines[2].format(samples=settling["samples"], judged=settling["judged"],
                               step=directions[1] - directions[0] if len(directions) > 1 else 360.0,
                               magnitudes=f"{magnitudes[0]:g} to {magnitudes[-1]:g}", settled=0.1)
    runs = [("this run", settling)]
    if off_grid is not None:
        grid = off_grid["directions_deg"]
        runs.append((f"off the grid ({off_grid['date']})", off_grid))
        lines += ["", f"\"Off the grid\" is `bench/settling.py --off-grid`, run on {off_grid['date']}: the "
                  f"directions between the full sweep's (every {grid[1] - grid[0]:g} deg from {grid[0]:g}) at "
                  f"{off_grid['magnitudes'][0]:g} to {off_grid['magnitudes'][-1]:g} times the capability; it is "
                  "kept in `bench/results/settling_offgrid.json`, not re-measured by `make bench` (about 20 "
                  "minutes on one core)."]
    lines += ["", "| run | vessel | method | not at rest | largest spread deg | fallbacks, all samples | "
              "worst deviation | violations | median us | p99 us | max us |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for label, run in runs:
        for vessel, methods in run["vessels"].items():
            for method, summary in methods.items():
                times = summary["time_us"]
                lines.append(f"| {label} | {vessel} | {method} | {summary['moving_or_falling_back']} of "
                             f"{summary['cases']} | {_fmt(summary.get('largest_spread_deg'), 3)} | "
                             f"{100 * summary['fallback_share']:.2f} % | "
                             f"{_fmt(summary['worst_deviation'], 4)} | {summary['violations']} | "
                             f"{_fmt(times['median'], 0)} | {_fmt(times['p99'], 0)} | {_fmt(times['max'], 0)} |")
    return lines


def _inprocess_section(run: dict) -> list[str]:
    """The in-process closed loop's real-time factor against the node in the loop (bench/inprocess_sim.py)."""
    inside = run["in_process"]
    lines = ["## Closed loop in process", "",
             f"`bench/inprocess_sim.py`: `{run['scenario']}` ({run['duration_s']:g} s simulated, method "
             f"{run['method']}) with the allocator library in the loop (`allocator-sim --in-process`), the median "
             f"of {run['repeats']} runs, and one run with `allocator_node` in the loop; simulated seconds per "
             "second of the whole run (wall clock, and CPU of this process and its children).", "",
             "| | wall, steps only | wall, whole run | CPU, whole run |", "|---|---|---|---|",
             f"| in process | {inside['loop']:.0f}x | {inside['run']:.0f}x | {inside['run_cpu']:.0f}x |"]
    if "node" in run:
        node, ratio = run["node"], run["ratio"]
        lines += [f"| node in the loop | {node['loop']:.0f}x | {node['run']:.0f}x | {node['run_cpu']:.0f}x |",
                  f"| ratio | {ratio['loop']:.1f} | {ratio['run']:.1f} | {ratio['run_cpu']:.1f} |"]
    lines += ["", f"Target: at least {run['target']:g}x real time on one core (CPU): "
              f"{'met' if run['meets_target'] else 'not met'}."]
    return lines


def _level3_section(run: dict, study: dict | None = None) -> list[str]:
    """The cost of a Level 3 case and the pool's speed-up (bench/dp_level3.py), and the speed-up of
    a short study's search when measured (``--study``)."""
    inside = run["in_process"]
    lines = ["## DP capability Level 3", "",
             f"`bench/dp_level3.py`: {run['cases']} fixed cases on {run['vessel']} "
             f"({run['simulated_s_per_case']:g} s simulated each), in this process, then on a pool of one and of "
             "two workers (start-up included); the results of the three are compared.", "",
             "| s per case (wall) | cases per minute | real-time factor (wall / CPU) | 1 worker s | 2 workers s | "
             "speed-up | target | identical |", "|---|---|---|---|---|---|---|---|",
             f"| {inside['wall_s_per_case']:.2f} | {inside['cases_per_minute']:.1f} | "
             f"{inside['realtime_factor_wall']:.0f}x / {inside['realtime_factor_cpu']:.0f}x | "
             f"{run['pool_1_worker']['wall_s']:.1f} | {run['pool_2_workers']['wall_s']:.1f} | "
             f"{run['speedup_2_over_1']:.2f} | >= {run['target_speedup']:g} | {'yes' if run['identical'] else 'no'} |"]
    if study is None:
        return lines
    return [
        *lines, "",
        f"`bench/dp_level3.py --study`: the rising search of dp_vessel every 90 deg, {study['seeds']} seeds a "
        f"condition, {study['simulated_s_per_run']:g} s simulated a run, on one and on two workers, journal "
        "included; load average before each.", "",
        "| runs | 1 worker s (load) | 2 workers s (load) | speed-up | target | journals identical |",
        "|---|---|---|---|---|---|",
        f"| {study['runs']} | {study['pool_1_worker']['wall_s']:.1f} ({study['pool_1_worker']['load_average']:.1f}) | "
        f"{study['pool_2_workers']['wall_s']:.1f} ({study['pool_2_workers']['load_average']:.1f}) | "
        f"{study['speedup_2_over_1']:.2f} | >= {study['target_speedup']:g} | "
        f"{'yes' if study['identical_journals'] else 'no'} |"]


STEP_PARTS = (("allocator_link_besides_allocate", "the link's own work (power drawn per source, sample rules)"),
              ("control_and_observer", "control system (measurement, observer, controller)"),
              ("thrusters", "simulated thrusters"), ("hull_environment_trace", "hull, environment, trace"))


def _step_costs_section(run: dict) -> list[str]:
    """Everything but allocate() in a Level 3 step against allocate() (bench/dp_step_costs.py)."""
    split, ratios = run["split_us_per_step"], run["split_ratio_to_allocate"]
    lines = ["## A Level 3 step against allocate()", "",
             f"`bench/dp_step_costs.py`: {run['case']}, {run['steps']} steps after the warm-up, process time. "
             "Everything but `Allocator.allocate` is the run's steps less it: the in-process link's own "
             "per-sample work (the node's beside the solve), the control system, the thrusters, the hull, "
             "the environment, the events and the trace.", "",
             "| allocate() us | everything else us | ratio | target |", "|---|---|---|---|",
             f"| {run['allocate_us']:.0f} | {run['all_but_allocate_us']:.0f} | "
             f"{run['all_but_allocate_over_allocate']:.2f} | <= {run['target_ratio']:g} |", "",
             f"The split, from a second run with every part timed ({run['timer_us_per_call']:.1f} us of clock "
             "reads per timed call fall on the parts):", "", "| part | us per step | against allocate() |",
             "|---|---|---|"]
    lines += [f"| {label} | {split[key]:.0f} | {ratios[key]:.2f} |" for key, label in STEP_PARTS]
    return lines


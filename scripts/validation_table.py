#!/usr/bin/env python3
"""The results table of docs/validation.md from `dynrad validate --json FILE`.

    build/plugin/dynrad validate --json v.json && scripts/validation_table.py v.json

One row per section and title (5.2, 5.3, ...; the facade openings over a grey ground
apart): its runs and points, the worst error of the lit mesh's points, of the grids'
points and of the area (flux) checks, the mean over all its points, the goal, CIE 171's
tolerance, the worst error against the reference alone ("strict"), and the seconds its
solves and probes took, summed. A section with a run over its goal is marked.
"""
import json
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    runs = json.load(open(sys.argv[1]))
    sections = []
    for run in runs:
        title = run["title"]  # a section's runs over a grey ground have a title of their own
        if not sections or (sections[-1]["id"], sections[-1]["title"]) != (run["case"], title):
            sections.append({"id": run["case"], "title": title, "runs": 0, "points": 0, "mesh": None,
                             "grid": None, "area": None, "sum": 0.0, "strict": 0.0, "goal": run["goal"],
                             "cie": run["cie_tolerance"], "seconds": 0.0, "passed": True})
        s = sections[-1]
        s["runs"] += 1
        s["seconds"] += run["seconds"]
        s["passed"] = s["passed"] and run["passed"]
        s["strict"] = max(s["strict"], run["strict_worst"])
        for p in run["points"]:
            kind = p["where"].split(" ")[0]
            key = {"mesh": "mesh", "grid": "grid", "area": "area"}.get(kind, "area")
            s[key] = max(s[key] or 0.0, p["error"])
            s["points"] += 1
            s["sum"] += p["error"]

    def percent(v):
        return "-" if v is None else f"{100 * v:.2f}%"

    print("| case | what | runs | points | worst, lit mesh | worst, grids | worst, areas | mean | goal | CIE "
          "| strict worst | time |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in sections:
        mean = s["sum"] / s["points"] if s["points"] else 0.0
        mark = "" if s["passed"] else " **over**"
        print(f"| {s['id']} | {s['title']} | {s['runs']} | {s['points']} | {percent(s['mesh'])} | "
              f"{percent(s['grid'])} | {percent(s['area'])} | {100 * mean:.3f}% | {100 * s['goal']:.0f}% | "
              f"{100 * s['cie']:.0f}% | {percent(s['strict'])} | {s['seconds']:.0f} s |{mark}")


if __name__ == "__main__":
    main()

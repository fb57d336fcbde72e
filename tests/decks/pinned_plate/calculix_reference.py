"""The pin reactions of CalculiX's run of a pinned plate deck, as CSV rows.

    python3 calculix_reference.py JOB.dat [JOB.dat ...] > calculix_reactions.csv

Reads the "total force (fx,fy,fz) for set ... and time ..." blocks that
the deck's *NODE PRINT, TOTALS=ONLY cards make CalculiX write into its
.dat, and keeps the last time of each set: the reactions RF1, RF2 summed
over the set (CalculiX prints its expanded 3D nodes' forces summed onto
the 2D nodes). Rows: deck (the job name), set, time, RF1, RF2.
"""
import csv
import os
import re
import sys


def number(text):
    """A CalculiX number, also in its exponent-less form 1.234-182."""
    return float(re.sub(r"(\d)([+-]\d{3})$", r"\1e\2", text))


def totals(dat):
    """(set, time) -> (fx, fy) of the TOTALS blocks of a .dat, in order."""
    out = {}
    with open(dat) as f:
        lines = f.read().splitlines()
    for k, line in enumerate(lines):
        m = re.match(r"\s*total force \(fx,fy,fz\) for set (\S+) and time\s+(\S+)", line)
        if not m:
            continue
        values = next(lines[j] for j in range(k + 1, len(lines)) if lines[j].strip()).split()
        out[m.group(1), float(m.group(2))] = (number(values[0]), number(values[1]))
    return out


def main(dats):
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["deck", "set", "time", "RF1", "RF2"])
    for dat in dats:
        name = os.path.splitext(os.path.basename(dat))[0]
        last = {}
        for (s, t), f in totals(dat).items():
            last[s] = (t, f)       # the .dat is in time order: the last one stays
        for s, (t, (fx, fy)) in last.items():
            out.writerow([name, s, f"{t:.7g}", f"{fx:.6e}", f"{fy:.6e}"])


if __name__ == "__main__":
    main(sys.argv[1:])

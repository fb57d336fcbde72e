#!/usr/bin/env python3
"""Run CalculiX's own test decks with 2D elements through cfe2d.

Takes the test/ folder of a CalculiX source tree (it is not part of cfe2d:
fetch or unpack it anywhere), picks every deck with 2D continuum elements
(CPS*, CPE*, CAX*, also in included files), runs cfe2d on it unchanged and
sorts the outcome:

  ran       exit status 0; the displacements are compared with CalculiX's
            <deck>.dat.ref (its *NODE PRINT output) and <deck>.frd.ref (its
            *NODE FILE output, ASCII) at the times both hold (largest
            difference over the largest reference displacement, common nodes
            only); each comparison names the file it used
  rejected  exit status 1 with "file:line: error: ..." (the first cause)
  crashed   anything else: a signal, a Fortran runtime error, a timeout

The comparison is meaningful for plane strain and axisymmetric decks;
CalculiX expands plane-stress elements into a layer of 3D bricks, whose
answer differs from 2D plane stress by a few per cent, so those are
reported but not judged. With *NODE FILE, OUTPUT=3D CalculiX writes the
nodes of its expanded 3D elements (new node numbers) instead of the deck's
own: such a .frd.ref is reported as holding only expanded nodes, not
compared.

  python3 scripts/calculix_suite.py CALCULIX/test [--cfe2d bin/cfe2d]
          [--out results/calculix] [--markdown docs/calculix-suite.md]
"""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from cfe2d_listing import read_listing  # noqa: E402
from gmsh_results import read_msh  # noqa: E402

__all__ = ["deck_element_types", "deck_keywords", "cfe2d_keywords", "run_deck", "read_dat_displacements",
           "read_frd_displacements", "frd_by_time", "cfe2d_displacements", "compare_displacements",
           "compare_references", "main"]

PLANE = re.compile(r"^(CPS|CPE|CAX)", re.I)
TOLERANCE = 1e-3


def deck_element_types(path, seen=None):
    """Element type names of a deck and the files it includes (upper case);
    missing include files are skipped."""
    seen = seen if seen is not None else set()
    types = []
    if path in seen or not os.path.isfile(path):
        return types
    seen.add(path)
    with open(path, errors="replace") as f:
        for line in f:
            s = line.strip()
            if not s.startswith("*") or s.startswith("**"):
                continue
            head = s.upper().replace(" ", "")
            m = re.search(r"TYPE=([A-Z0-9]+)", head)
            if head.startswith("*ELEMENT,") and m:
                types.append(m.group(1))
            m = re.search(r"INPUT=([^,]+)", s, re.I)
            if head.startswith("*INCLUDE") and m:
                types += deck_element_types(os.path.join(os.path.dirname(path), m.group(1).strip()), seen)
    return types


def deck_keywords(path, seen=None):
    """Keyword names of a deck and its includes, in order of first use."""
    seen = seen if seen is not None else set()
    names = []
    if path in seen or not os.path.isfile(path):
        return names
    seen.add(path)
    with open(path, errors="replace") as f:
        for line in f:
            s = line.strip()
            if not s.startswith("*") or s.startswith("**"):
                continue
            name = " ".join(s[1:].split(",")[0].upper().split())
            if name == "INCLUDE":
                m = re.search(r"INPUT=([^,]+)", s, re.I)
                if m:
                    names += deck_keywords(os.path.join(os.path.dirname(path), m.group(1).strip()), seen)
            if name not in names:
                names.append(name)
    return names


def cfe2d_keywords(parser=os.path.join(ROOT, "src", "input", "deck_parser.f90")):
    """The keywords cfe2d reads (or skips with a warning): the case labels
    of the parser's dispatch, read from its source so that the list follows
    the program."""
    with open(parser) as f:
        text = f.read()
    body = text[text.index("subroutine dispatch"):text.index("end subroutine dispatch")]
    body = body.replace("&\n", " ")
    names = set()
    for labels in re.findall(r"case \(([^)]*)\)", re.sub(r"&\s*\n\s*", " ", body)):
        names.update(re.findall(r"'([^']+)'", labels))
    names.discard("")
    return names | {"INCLUDE"}


def stress_state(types):
    states = sorted({{"CPS": "plane stress", "CPE": "plane strain", "CAX": "axisymmetric"}[t[:3]]
                     for t in types if PLANE.match(t)})
    return ", ".join(states)


def run_deck(cfe2d, deck, outdir, timeout):
    """(status, detail, listing path): status ran / rejected / crashed."""
    os.makedirs(outdir, exist_ok=True)
    try:
        proc = subprocess.run([cfe2d, "-q", "-d", "16", "-o", outdir, deck], capture_output=True, text=True,
                              timeout=timeout, errors="replace")
    except subprocess.TimeoutExpired:
        return "crashed", f"no answer within {timeout} s", None
    listing = os.path.join(outdir, os.path.splitext(os.path.basename(deck))[0] + ".out")
    errors = [line for line in proc.stderr.splitlines() if ": error: " in line]
    if proc.returncode == 0:
        return "ran", "", listing
    if proc.returncode == 1 and errors:
        first = errors[0]
        # file:line relative to the test folder
        first = first.replace(os.path.dirname(deck) + "/", "")
        return "rejected", first, None
    tail = proc.stderr.strip().splitlines()[-1:] or [""]
    return "crashed", f"exit status {proc.returncode}: {tail[0][:160]}", None


def read_dat_displacements(path):
    """{time: {node: (u1, u2)}} of the 'displacements' blocks of a .dat file
    (the last block of a time wins)."""
    out = {}
    block = None
    with open(path, errors="replace") as f:
        for line in f:
            m = re.match(r"\s*displacements \(vx,vy,vz\) for set \S+ and time\s+(\S+)", line)
            if m:
                block = out.setdefault(float(m.group(1)), {})
                continue
            parts = line.split()
            if block is not None and len(parts) >= 3 and parts[0].isdigit():
                try:
                    block[int(parts[0])] = (float(parts[1]), float(parts[2]))
                except ValueError:
                    block = None
            elif parts and block is not None and not parts[0].isdigit():
                block = None
    return out


def _frd_number(text):
    """A field of a .frd record; a blank field is 0, as Fortran reads it."""
    text = text.strip()
    return float(text) if text else 0.0


def read_frd_displacements(path):
    """The displacement blocks of an ASCII CalculiX result file (.frd), in
    file order: a list of dicts with step, increment (from the 1PSTEP
    record before the block), time (the total time of its 100C record) and
    u {node: (d1, d2, d3)} (its -1 records, fixed columns: the values may
    touch). Other result blocks are skipped. A binary file, or a record
    that cannot be read, is a ValueError naming the line."""
    out = []
    step = inc = 0
    head = None                 # (time, node field width) of the last 100C record
    block = None
    with open(path, "rb") as f:
        data = f.read()
    if b"\0" in data:
        raise ValueError(f"{path}: a binary .frd is not read")
    for no, raw in enumerate(data.decode("latin-1").splitlines(), 1):
        # data records start with " -n" (the node number may follow without
        # a blank), header records with a counter and a name: "    1PSTEP"
        key = raw[:3].strip() if raw[:2] == " -" else (raw.split() or [""])[0]
        try:
            if key == "1PSTEP":
                # counter, increment, step in columns 25-36, 37-48, 49-60 (blank: 0)
                inc, step = (int(raw[a:a + 12].strip() or 0) for a in (36, 48))
            elif key.startswith("100C"):
                # column 75 is the format: 0 short (5-digit node numbers), 1 long (10)
                width = 5 if raw[74:75] == "0" else 10
                head = (_frd_number(raw[12:24]), width)
                block = None
            elif key == "-4":
                block = None
                if raw[3:].split()[0] == "DISP":
                    if head is None:
                        raise ValueError("a -4 DISP block without its 100C record")
                    block = {"step": step, "increment": inc, "time": head[0], "u": {}}
                    out.append(block)
            elif key == "-1" and block is not None:
                w = head[1]
                vals = raw[3 + w:]
                block["u"][int(raw[3:3 + w])] = tuple(_frd_number(vals[12 * k:12 * k + 12]) for k in range(3))
            elif key == "-3":
                block = None
        except (ValueError, IndexError) as e:
            raise ValueError(f"{path}:{no}: cannot read the record ({e})") from None
    return out


def frd_by_time(datasets):
    """{time: {node: (d1, d2)}} of read_frd_displacements' blocks (the
    last block of a time wins), the in-plane components."""
    out = {}
    for d in datasets:
        out[d["time"]] = {n: v[:2] for n, v in d["u"].items()}
    return out


def cfe2d_displacements(listing_path):
    """cfe2d's displacements {time: {node: (u1, u2)}} from the listing's
    NODE U blocks (*NODE PRINT) and the Displacement views of <job>.msh
    (*NODE FILE), and the model's node ids (all of them when the result
    file exists, else those printed)."""
    out, nodes = {}, set()
    for inc in read_listing(listing_path).increments:
        for b in inc.blocks:
            if b.name == "NODE U":
                vals = out.setdefault(inc.time, {})
                for node, u1, u2 in zip(b["node"], b["U1"], b["U2"]):
                    vals[int(node)] = (u1, u2)
                    nodes.add(int(node))
    msh = listing_path[:-4] + ".msh"
    if os.path.exists(msh):
        res = read_msh(msh)
        nodes = {int(n) for n in res.node_ids}
        for time, ids, vals in res.views.get("Displacement", []):
            block = out.setdefault(time, {})
            for n, v in zip(ids, vals):
                block[int(n)] = (float(v[0]), float(v[1]))
    return out, nodes


def _same_time(a, b):
    # small times are printed with 6 significant digits in a .frd
    return abs(a - b) <= 1e-5 * max(abs(a), abs(b)) or abs(a - b) <= 1e-12


def compare_displacements(ours, ref):
    """Largest |u_cfe2d - u_ref| / largest |u_ref| over the nodes and times
    both hold (None when they share none), and the number of values
    compared. ours, ref: {time: {node: (u1, u2)}}."""
    worst, scale, count = 0.0, 0.0, 0
    for time, values in ours.items():
        t = min(ref, key=lambda r: abs(r - time), default=None)
        if t is None or not _same_time(t, time):
            continue
        for node, (u1, u2) in values.items():
            r = ref[t].get(node)
            if r is None:
                continue
            worst = max(worst, abs(u1 - r[0]), abs(u2 - r[1]))
            scale = max(scale, abs(r[0]), abs(r[1]))
            count += 1
    if count == 0:
        return None, 0
    return (worst / scale if scale > 0 else worst), count


def judge(state, rel, count=0):
    """The comparison's text: the difference, how many node values (nodes
    times output times) it took, and the verdict."""
    if rel is None:
        return "no common output"
    text = f"largest difference {rel:.2e} of the largest displacement over {count} node values"
    if state in ("plane strain", "axisymmetric"):
        return text + (" (agrees)" if rel <= TOLERANCE else " (DIFFERS)")
    return text + " (plane stress: CalculiX solves a 3D layer, not judged)"


def compare_frd(ours, nodes, path, state):
    """The comparison text of a .frd.ref: only the deck's own nodes count
    (with OUTPUT=3D CalculiX writes its expanded nodes, numbered after
    them, instead)."""
    try:
        datasets = read_frd_displacements(path)
    except ValueError as e:
        return f"not read ({e})"
    held = set().union(*(d["u"] for d in datasets))
    if not held:
        return "no displacements"
    if not held & nodes:
        return "only the expanded 3D nodes (OUTPUT=3D), none of the deck's: not compared"
    return judge(state, *compare_displacements(ours, frd_by_time(datasets)))


def compare_references(listing, testdir, job, state):
    """The comparisons of a deck that ran, one per reference file present,
    each naming its file: ".dat.ref: ...; .frd.ref: ..."."""
    ours, nodes = cfe2d_displacements(listing)
    parts = []
    dat = os.path.join(testdir, job + ".dat.ref")
    if os.path.exists(dat):
        parts.append(".dat.ref: " + judge(state, *compare_displacements(ours, read_dat_displacements(dat))))
    frd = os.path.join(testdir, job + ".frd.ref")
    if os.path.exists(frd):
        parts.append(".frd.ref: " + compare_frd(ours, nodes, frd, state))
    return "; ".join(parts) if parts else "no .dat.ref or .frd.ref"


def markdown(rows, testdir):
    counts = {k: sum(1 for r in rows if r["status"] == k) for k in ("ran", "rejected", "crashed")}
    lines = [f"{len(rows)} decks with 2D elements in `{testdir}`: {counts['ran']} ran, "
             f"{counts['rejected']} rejected, {counts['crashed']} crashed.", "",
             "| deck | elements | state | outcome | first cause / comparison with .dat.ref and .frd.ref | "
             "other cards cfe2d does not read |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['deck']} | {r['types']} | {r['state']} | {r['status']} | "
                     f"{r['detail'].replace('|', '/')} | {r['unread']} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("testdir", help="the test/ folder of a CalculiX source tree")
    ap.add_argument("--cfe2d", default=os.path.join(ROOT, "bin", "cfe2d"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "calculix"))
    ap.add_argument("--markdown", help="also write the table to this file")
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--quiet", action="store_true", help="print nothing (the table goes to --markdown)")
    args = ap.parse_args(argv)
    known = cfe2d_keywords()
    packed = {k.replace(" ", "") for k in known}
    rows = []
    for name in sorted(os.listdir(args.testdir)):
        if not name.endswith(".inp"):
            continue
        deck = os.path.join(args.testdir, name)
        types = deck_element_types(deck)
        plane = [t for t in types if PLANE.match(t)]
        if not plane:
            continue
        job = name[:-4]
        status, detail, listing = run_deck(args.cfe2d, deck, os.path.join(args.out, job), args.timeout)
        state = stress_state(plane)
        if status == "ran":
            detail = compare_references(listing, args.testdir, job, state)
        first = re.search(r"keyword \*(.+) is not implemented", detail)
        # (blanks do not count: cfe2d reads *SOLIDSECTION as *SOLID SECTION, as CalculiX does)
        unread = [k for k in deck_keywords(deck) if k.replace(" ", "") not in packed
                  and not (first and k == first.group(1))]
        rows.append({"deck": job, "types": ", ".join(sorted(set(types))), "state": state, "status": status,
                     "detail": detail, "unread": ", ".join("*" + k for k in unread)})
        if not args.quiet:
            print(f"{job:20s} {status:9s} {detail}", flush=True)
    text = markdown(rows, os.path.basename(os.path.normpath(args.testdir)))
    if not args.quiet:
        print()
        print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text)
    return rows


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Run CalculiX's own test decks with 2D elements through cfe2d.

Takes the test/ folder of a CalculiX source tree (it is not part of cfe2d:
fetch or unpack it anywhere), picks every deck with 2D continuum elements
(CPS*, CPE*, CAX*, also in included files), runs cfe2d on it unchanged and
sorts the outcome:

  ran       exit status 0; cfe2d's results are compared with CalculiX's
            <deck>.dat.ref and <deck>.frd.ref at the times both hold, each
            comparison naming its file, quantity and number of values
  rejected  exit status 1 with "file:line: error: ..." (the first cause)
  crashed   anything else: a signal, a Fortran runtime error, a timeout

What is compared (scripts/calculix_results.py reads the files and maps
CalculiX's expanded 3D output back to the 2D model):

  .dat.ref  *NODE PRINT displacements of the common nodes; *EL PRINT
            stresses S11, S22, S12 (and S33 but in plane stress) at the
            integration points, CalculiX's points of the expanded 3D
            element mapped back to the 2D element's (the middle layer, or
            the mean of the middle two); *CONTACT PRINT pressures, as the
            mean of the point pressures on each slave face
  .frd.ref  *NODE FILE displacements (ASCII) of the deck's nodes, or with
            OUTPUT=3D those of CalculiX's expanded nodes, averaged at each
            2D node they stand for (matched by (x, y); nodes sharing a
            position, as a pre-tension's copies, split by element)

Displacements and stresses are the largest difference over the largest
reference value. They are judged ("agrees" within 1e-3, else "DIFFERS")
for plane strain and axisymmetric decks; CalculiX expands plane-stress
elements into a layer of 3D bricks, whose answer differs from 2D plane
stress by a few per cent, so those are reported but not judged. Contact
pressures are reported, never judged: CalculiX's surface-to-surface
contact integrates over face intersections, cfe2d couples points, and the
per-face means are only comparable, not the same quantity.

  python3 scripts/calculix_suite.py CALCULIX/test [--cfe2d bin/cfe2d]
          [--out results/calculix] [--markdown docs/calculix-suite.md]
"""
import argparse
import math
import os
import re
import subprocess
import sys
from collections import Counter

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from calculix_results import (expanded_displacements, frd_by_time, map_expanded_nodes,  # noqa: E402
                              read_dat_contact_stresses, read_dat_displacements, read_dat_stresses, read_dat_temperatures,
                              read_deck_mesh, read_frd_displacements, read_frd_mesh, stress_layers,
                              deck_face_polyline, nearest_face)
from cfe2d_listing import read_listing  # noqa: E402
from gmsh_results import read_msh  # noqa: E402

__all__ = ["deck_element_types", "deck_keywords", "cfe2d_keywords", "run_deck", "read_dat_displacements",
           "read_frd_displacements", "frd_by_time", "cfe2d_displacements", "cfe2d_mesh", "cfe2d_stresses",
           "cfe2d_contact", "compare_displacements", "compare_stresses", "contact_faces", "compare_references",
           "main"]

PLANE = re.compile(r"^(CPS|CPE|CAX|DC2D|DCAX)", re.I)   # (DC2D*, DCAX*: Abaqus's heat transfer names)
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
    # the dispatch and the routines it hands the other cards to (dispatch_*)
    body = "\n".join(m.group(0) for m in re.finditer(
        r"subroutine (dispatch\w*)\(.*?end subroutine \1", text, re.S))
    body = body.replace("&\n", " ")
    names = set()
    for labels in re.findall(r"case \(([^)]*)\)", re.sub(r"&\s*\n\s*", " ", body)):
        names.update(re.findall(r"'([^']+)'", labels))
    names.discard("")
    return names | {"INCLUDE"}


def stress_state(types):
    names = {"CPS": "plane stress", "CPE": "plane strain", "CAX": "axisymmetric", "DC2": "planar heat",
             "DCA": "axisymmetric"}
    states = sorted({names[t[:3].upper()] for t in types if PLANE.match(t)})
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


def cfe2d_temperatures(listing_path):
    """cfe2d's temperatures {time: {node: T}} from the listing's NODE NT
    blocks (*NODE PRINT NT)."""
    out = {}
    for inc in read_listing(listing_path).increments:
        for b in inc.blocks:
            if b.name == "NODE NT":
                vals = out.setdefault(inc.time, {})
                for node, t in zip(b["node"], b["NT11"]):
                    vals[int(node)] = t
    return out


def compare_temperatures(ours, ref):
    """Largest |T_cfe2d - T_ref| over the nodes and times both hold, over
    the range of T_ref there (its largest magnitude where it is uniform:
    temperatures carry an offset, so the range is the scale), and the
    number of values compared; (None, 0) when they share none."""
    worst, lo, hi, count = 0.0, math.inf, -math.inf, 0
    for time, values in ours.items():
        t = min(ref, key=lambda r: abs(r - time), default=None)
        if t is None or not _same_time(t, time):
            continue
        for node, v in values.items():
            r = ref[t].get(node)
            if r is None:
                continue
            worst = max(worst, abs(v - r))
            lo, hi = min(lo, r), max(hi, r)
            count += 1
    if count == 0:
        return None, 0
    scale = hi - lo if hi > lo else max(abs(lo), abs(hi))
    return (worst / scale if scale > 0 else worst), count


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


JUDGED = ("plane strain", "axisymmetric")


def judge(state, rel, count=0, quantity="displacement", values="node values"):
    """The comparison's text: the difference, how many values it took (node
    values: nodes times output times), and the verdict."""
    if rel is None:
        return "no common output"
    text = f"largest difference {rel:.2e} of the largest {quantity} over {count} {values}"
    if state in JUDGED:
        return text + (" (agrees)" if rel <= TOLERANCE else " (DIFFERS)")
    return text + " (plane stress: CalculiX solves a 3D layer, not judged)"


def cfe2d_mesh(listing_path):
    """cfe2d's model as <job>.msh holds it: ({node: (x, y)}, {element:
    [nodes]}) with the generated nodes (pre-tension copies) and the
    elements' nodes after the cut; (None, None) without the file."""
    msh = listing_path[:-4] + ".msh"
    if not os.path.exists(msh):
        return None, None
    res = read_msh(msh)
    xy = {int(n): (float(p[0]), float(p[1])) for n, p in zip(res.node_ids, res.xy)}
    return xy, {int(e): [int(n) for n in conn] for e, conn in zip(res.element_ids, res.elements)}


def cfe2d_stresses(listing_path):
    """{time: {element: {point: (S11, S22, S33, S12)}}} of the listing's
    ELEMENT S blocks (*EL PRINT S at the integration points)."""
    out = {}
    for inc in read_listing(listing_path).increments:
        for b in inc.blocks:
            if b.name == "ELEMENT S" and b.columns[:2] == ["element", "ip"]:
                block = out.setdefault(inc.time, {})
                cols = [b.columns.index(c) for c in ("S11", "S22", "S33", "S12")]
                for r in b.rows:
                    block.setdefault(int(r[0]), {})[int(r[1])] = tuple(float(r[c]) for c in cols)
    return out


def cfe2d_contact(listing_path):
    """{time: [(slave surface, x, y, pressure, share)]}: the slave points of
    the listing's CONTACT SLAVE blocks (cfe2d's coupling points); share is
    the sum of the listed slave forces of the point's pair over the pair's
    total force (CONTACT SUMMARY): 1 but for two-pass contact whose second
    pass's points are not listed."""
    out = {}
    for inc in read_listing(listing_path).increments:
        slaves, totals = {}, {}
        for b in inc.blocks:
            if b.name == "CONTACT SLAVE":
                slaves[b.attrs.get("pair")] = b
            elif b.name == "CONTACT SUMMARY" and len(b):
                totals[b.attrs.get("pair")] = float(b["total_force"][0])
        rows = out.setdefault(inc.time, [])
        for pair, b in slaves.items():
            total = totals.get(pair, 0.0)
            share = float(np.sum(b["force"])) / total if total else 1.0
            rows += [(b.attrs.get("surface", "?"), x, y, p, share) for x, y, p in zip(b["x"], b["y"], b["pressure"])]
    return out


def _at_time(ref, time):
    t = min(ref, key=lambda r: abs(r - time), default=None)
    return t if t is not None and _same_time(t, time) else None


def compare_stresses(ours, ref, state):
    """Largest difference of S11, S22, S12 (and S33 but in plane stress,
    where both are nearly 0) over the largest |reference component|, the
    number of 2D points compared and of elements whose point counts do
    not map (calculix_results.stress_layers), and the point counts met
    (sorted (CalculiX's, cfe2d's) pairs). ours: cfe2d_stresses; ref:
    read_dat_stresses."""
    comps = [(0, 0), (1, 1), (3, 3)] + ([] if state == "plane stress" else [(2, 2)])
    worst, scale, count, unmapped, kinds = 0.0, 0.0, 0, set(), set()
    for time, elements in ours.items():
        t = _at_time(ref, time)
        if t is None:
            continue
        for e, points in elements.items():
            theirs = ref[t].get(e)
            if not theirs:
                continue
            layers = stress_layers(len(theirs), len(points))
            if layers is None or any(q not in theirs for qs in layers for q in qs):
                unmapped.add(e)
                continue
            kinds.add((len(theirs), len(points)))
            for k, qs in enumerate(layers, 1):
                if k not in points:
                    continue
                r = np.mean([theirs[q] for q in qs], axis=0)
                worst = max(worst, max(abs(points[k][a] - r[b]) for a, b in comps))
                scale = max(scale, max(abs(r[b]) for _, b in comps))
                count += 1
    rel = None if count == 0 else (worst / scale if scale > 0 else worst)
    return rel, count, len(unmapped), sorted(kinds)


def _layers_text(kinds):
    words = []
    for n3, n2 in kinds:
        layers = n3 // n2
        if layers == 1:
            words.append(f"{n2} points, as printed")
        elif layers % 2:
            words.append(f"{n3} -> {n2}: the middle of {layers} layers")
        else:
            words.append(f"{n3} -> {n2}: the mean of the middle two of {layers} layers")
    return "; ".join(words)


def stresses_text(ours, ref, state):
    """The text of a stress comparison (None when nothing is common)."""
    rel, count, unmapped, kinds = compare_stresses(ours, ref, state)
    if rel is None and not unmapped:
        return None
    names = "S11, S22, S12" if state == "plane stress" else "S11, S22, S33, S12"
    text = f"stresses {names} (*EL PRINT) at CalculiX's 3D points mapped back ({_layers_text(kinds)}): "
    text += judge(state, rel, count, "stress", "integration points")
    if unmapped:
        text += f"; {unmapped} elements whose point counts do not map, not compared"
    return text


def compare_dat(listing, path, state, deck):
    """The comparison text of a .dat.ref: displacements (*NODE PRINT),
    stresses (*EL PRINT) and contact pressures (*CONTACT PRINT), those
    both files hold."""
    ours, _ = cfe2d_displacements(listing)
    parts = []
    disp = read_dat_displacements(path)
    rel, count = compare_displacements(ours, disp)
    if rel is not None:
        parts.append("displacements: " + judge(state, rel, count))
    rel, count = compare_temperatures(cfe2d_temperatures(listing), read_dat_temperatures(path))
    if rel is not None:
        # (a plane-stress layer conducts as the plane: judged in every state)
        text = judge(JUDGED[0], rel, count, "temperature range")
        parts.append("temperatures: " + text)
    text = stresses_text(cfe2d_stresses(listing), read_dat_stresses(path), state)
    if text:
        parts.append(text)
    contact = read_dat_contact_stresses(path)
    if contact:
        parts.append(contact_text(listing, contact, deck))
    return ", ".join(parts) if parts else "no common output"


def contact_faces(points, ref, deck):
    """Contact pressures per slave face, both programs'.

    points: cfe2d's slave points [(surface, x, y, pressure, share)] at one
    time (cfe2d_contact); ref: CalculiX's [(element, face, pressure)]
    (face of the expanded 3D element: 2D face = face - 2); deck: the
    deck's path (its mesh places the faces). Each cfe2d point goes to the
    CalculiX face nearest to it (within 5 % of the face's length).
    Returns (rows, stray, unplaced): rows {(element, 2D face): {"surface",
    "share", "ccx": [pressures], "cfe2d": [pressures]}}, stray: the cfe2d
    points near none of CalculiX's faces [(surface, pressure)], unplaced:
    CalculiX's faces not in the deck's mesh."""
    nodes, elements = read_deck_mesh(deck)
    rows, lines, unplaced = {}, {}, set()
    for e, f3, p in ref:
        key = (e, f3 - 2)
        if key not in lines and key not in unplaced:
            etype, conn = elements.get(e, ("", []))
            chain = deck_face_polyline(etype, conn, f3 - 2) if conn else None
            if chain is None or any(n not in nodes for n in chain):
                unplaced.add(key)
                continue
            lines[key] = [nodes[n] for n in chain]
        if key in lines:
            rows.setdefault(key, {"surface": "", "share": 1.0, "ccx": [], "cfe2d": []})["ccx"].append(p)
    stray = []
    for surface, x, y, p, share in points:
        key, rel = nearest_face((x, y), lines)
        if key is None or rel > 0.05:
            stray.append((surface, p))
            continue
        rows[key].update(surface=surface, share=share)
        rows[key]["cfe2d"].append(p)
    return rows, stray, sorted(unplaced)


def _pct(v):
    return f"{100 * v:.0f} %" if 100 * v >= 9.95 else f"{100 * v:.2g} %"


def _face_differences(faces, scale=1.0):
    """(smallest, largest relative difference, face of the largest) of the
    mean pressure per face, cfe2d's times scale against CalculiX's."""
    diff = {}
    for key, v in faces.items():
        ref = float(np.mean(v["ccx"]))
        diff[key] = abs(scale * np.mean(v["cfe2d"]) - ref) / abs(ref) if ref else np.inf
    worst = max(diff, key=diff.get)
    return min(diff.values()), diff[worst], worst


def contact_text(listing, ref, deck):
    """The text of a contact-pressure comparison (*CONTACT PRINT), reported
    and not judged: per cfe2d slave surface, the range of the differences
    of the mean pressure per slave face from CalculiX's (and the face of
    the largest); when the listed points carry only part of their pair's
    force (two-pass contact: the second pass's points are not listed),
    also the range with cfe2d's pressures scaled to the pair's total; the
    faces only one side has points on. The rows go to
    <job>_contact_vs_ccx.csv beside the listing."""
    ours = cfe2d_contact(listing)
    pairs = [(t, _at_time(ref, t)) for t in sorted(ours)]
    pairs = [(t, r) for t, r in pairs if r is not None]
    if not pairs:
        return "contact pressures: no common output time"
    t, r = pairs[-1]
    rows, stray, unplaced = contact_faces(ours[t], ref[r], deck)
    csv = listing[:-4] + "_contact_vs_ccx.csv"
    with open(csv, "w") as f:
        f.write("time,element,face,surface,ccx_points,ccx_mean_pressure,cfe2d_points,cfe2d_mean_pressure,"
                "cfe2d_share_of_pair_force\n")
        for (e, k), v in sorted(rows.items()):
            cm = np.mean(v["ccx"]) if v["ccx"] else float("nan")
            om = np.mean(v["cfe2d"]) if v["cfe2d"] else float("nan")
            f.write(f"{t:.6e},{e},S{k},{v['surface']},{len(v['ccx'])},{cm:.6e},{len(v['cfe2d'])},{om:.6e},"
                    f"{v['share']:.6f}\n")
    text = (f"contact pressure (*CONTACT PRINT) at time {t:g}, the mean of the point pressures on each slave face "
            f"(CalculiX: its face-intersection points, unweighted: it prints no weights; cfe2d: its coupling "
            f"points), reported, not judged: ")
    words = []
    for surface in sorted({v["surface"] for v in rows.values() if v["cfe2d"]}):
        faces = {key: v for key, v in rows.items() if v["surface"] == surface and v["cfe2d"]}
        lo, hi, (e, k) = _face_differences(faces)
        word = (f"{surface}: {len(faces)} faces ({sum(len(v['ccx']) for v in faces.values())} CalculiX points, "
                f"{sum(len(v['cfe2d']) for v in faces.values())} cfe2d points), difference {_pct(lo)} to "
                f"{_pct(hi)} of CalculiX's mean (largest at element {e} face S{k}: cfe2d "
                f"{np.mean(faces[(e, k)]['cfe2d']):.3g}, CalculiX {np.mean(faces[(e, k)]['ccx']):.3g})")
        share = faces[(e, k)]["share"]
        if abs(share - 1.0) > 1e-3:
            lo, hi, (e, k) = _face_differences(faces, 1.0 / share)
            word += (f"; its listed points carry {share:.3f} of the pair's total force (two-pass contact, the "
                     f"second pass's points are not listed): scaled by 1/{share:.3f}, difference {_pct(lo)} "
                     f"to {_pct(hi)} (largest at element {e} face S{k}: cfe2d "
                     f"{np.mean(faces[(e, k)]['cfe2d']) / share:.3g}, CalculiX {np.mean(faces[(e, k)]['ccx']):.3g})")
        words.append(word)
    only_ccx = [key for key, v in rows.items() if not v["cfe2d"]]
    if only_ccx:
        words.append(f"{len(only_ccx)} faces with CalculiX points and no cfe2d point")
    if stray:
        words.append(f"{len(stray)} cfe2d points on faces CalculiX prints no pressure for "
                     f"(largest absolute pressure {max(abs(p) for _, p in stray):.3g})")
    if unplaced:
        words.append(f"{len(unplaced)} CalculiX faces not found in the deck's mesh")
    return text + "; ".join(words) + f" (per face: {os.path.basename(csv)})"


def expanded_frd_text(ours, listing, path, datasets, state, deck):
    """The comparison of a .frd.ref holding only CalculiX's expanded 3D
    nodes (OUTPUT=3D): their mean at each 2D node (map_expanded_nodes)."""
    if "axisymmetric" in state:
        return ("only the expanded 3D nodes (OUTPUT=3D) of an axisymmetric model (a wedge, "
                "rotated components): not mapped back, not compared")
    xy, elements = cfe2d_mesh(listing)
    if xy is None:
        return "only the expanded 3D nodes (OUTPUT=3D), and no <job>.msh for cfe2d's coordinates: not compared"
    try:
        frd_xyz, frd_elements = read_frd_mesh(path)
    except ValueError as e:
        return f"not read ({e})"
    if not frd_xyz:
        return "only the expanded 3D nodes (OUTPUT=3D), and no node block (2C) to place them: not compared"
    _, deck_elements = read_deck_mesh(deck)
    # trusses and springs are not in <job>.msh: their nodes come from the deck
    for e, (_, conn) in deck_elements.items():
        elements.setdefault(e, conn)
    groups, coincident, off = map_expanded_nodes(frd_xyz, frd_elements, xy, elements)
    rel, count = compare_displacements(ours, expanded_displacements(datasets, groups))
    places = Counter(xy[n] for n in groups)
    shared = sum(1 for n in groups if places[xy[n]] > 1)
    text = (f"displacements of the expanded 3D nodes (OUTPUT=3D), their mean at each of {len(groups)} "
            f"of cfe2d's nodes (matched by (x, y)")
    text += f"; {shared} nodes sharing a position split by element): " if shared else "): "
    text += judge(state, rel, count)
    if coincident:
        text += (f"; {len(coincident)} nodes at positions shared by several nodes (pre-tension copies) "
                 f"cannot be matched by coordinates, not compared")
    if off:
        text += f"; {len(off)} nodes whose expanded nodes do not centre on them, not compared"
    return text


def own_nodes(common, path, listing):
    """Whether the numbers both cfe2d and the .frd hold (common) are the
    deck's nodes: none in common, no; else yes, unless both files give
    coordinates and one of these nodes is elsewhere (expanded nodes may
    carry numbers cfe2d uses, as for nodes it generated)."""
    if not common:
        return False
    xy = cfe2d_mesh(listing)[0] if listing else None
    try:
        frd_xyz = read_frd_mesh(path)[0] if xy else {}
    except ValueError:
        frd_xyz = {}
    if not xy or not frd_xyz:
        return True
    tol = 1e-6 * float(np.ptp(np.array(list(xy.values())), axis=0).max())
    return all(n in frd_xyz and n in xy and max(abs(frd_xyz[n][0] - xy[n][0]), abs(frd_xyz[n][1] - xy[n][1])) <= tol
               for n in common)


def compare_frd(ours, nodes, path, state, listing=None, deck=None):
    """The comparison text of a .frd.ref: the deck's own nodes by number,
    or, when it holds only CalculiX's expanded nodes (OUTPUT=3D, numbered
    after the deck's), these mapped back to cfe2d's nodes by coordinates
    (needs the listing's <job>.msh and the deck)."""
    try:
        datasets = read_frd_displacements(path)
    except ValueError as e:
        return f"not read ({e})"
    held = set().union(*(d["u"] for d in datasets))
    if not held:
        return "no displacements"
    if not own_nodes(held & nodes, path, listing):
        if listing is None or deck is None:
            return "only the expanded 3D nodes (OUTPUT=3D), none of the deck's: not compared"
        return expanded_frd_text(ours, listing, path, datasets, state, deck)
    return judge(state, *compare_displacements(ours, frd_by_time(datasets)))


def compare_references(listing, testdir, job, state):
    """The comparisons of a deck that ran, one per reference file present,
    each naming its file: ".dat.ref: ...; .frd.ref: ..."."""
    deck = os.path.join(testdir, job + ".inp")
    ours, nodes = cfe2d_displacements(listing)
    parts = []
    dat = os.path.join(testdir, job + ".dat.ref")
    if os.path.exists(dat):
        parts.append(".dat.ref: " + compare_dat(listing, dat, state, deck))
    frd = os.path.join(testdir, job + ".frd.ref")
    if os.path.exists(frd):
        parts.append(".frd.ref: " + compare_frd(ours, nodes, frd, state, listing, deck))
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

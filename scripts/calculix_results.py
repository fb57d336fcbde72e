"""Read CalculiX's reference results and map them onto a 2D model.

CalculiX solves 2D elements as 3D ones: it expands each plane or
axisymmetric element into a layer of bricks (a thin wedge for
axisymmetric ones) and each truss into a thin beam of bricks. What its
files hold follows from that:

  .dat  *NODE PRINT displacements of the deck's own nodes; *EL PRINT
        stresses at the integration points of the expanded 3D element;
        *CONTACT PRINT pressures at the points of its face intersections
  .frd  *NODE FILE displacements (ASCII), of the deck's nodes or, with
        OUTPUT=3D, of the expanded nodes only (new numbers, after the
        deck's; the file's node block (2C) gives their coordinates and its
        element block (3C) the expanded elements under the deck's numbers)

The readers here take these files apart; the mappings bring the 3D values
back to the 2D model:

  expanded nodes   each goes to the 2D node nearest in (x, y): a node of a
                   plane element has copies at the same (x, y) (different
                   z), a truss end four corners of a small square around
                   it; the 2D value is their mean (map_expanded_nodes)
  stress points    the points of an expanded element come layer by layer
                   through the thickness, each layer in the order of the
                   2D element's points; the middle layer (or the mean of
                   the two middle ones) is the 2D element (stress_layers)
  contact faces    face f of an expanded element is face f - 2 of the 2D
                   element (faces 1 and 2 are the brick's front and back)
                   (deck_face_polyline)
"""
import os
import re

import numpy as np

__all__ = ["read_dat_displacements", "read_dat_stresses", "read_dat_contact_stresses", "read_dat_slave_node_contact",
           "read_dat_set_forces", "read_frd_displacements",
           "read_frd_mesh", "frd_by_time", "read_deck_mesh", "map_expanded_nodes", "expanded_displacements",
           "stress_layers", "deck_face_polyline", "nearest_face"]


# --- .dat ------------------------------------------------------------------

def _dat_blocks(path, header):
    """{time: [rows]} of the .dat blocks whose title starts with header:
    the rows are the lists of numbers of the lines that start with an
    integer; a block ends at the first other line that is not blank.
    Blocks of the same time (several sets) add up, in file order."""
    title = re.compile(r"\s*" + re.escape(header) + r".*\band time\s+(\S+)")
    out, block = {}, None
    with open(path, errors="replace") as f:
        for line in f:
            m = title.match(line)
            if m:
                block = out.setdefault(float(m.group(1)), [])
                continue
            parts = line.split()
            if block is None or not parts:
                continue
            if not parts[0].isdigit():
                block = None
                continue
            try:
                block.append([int(parts[0])] + [float(v) for v in parts[1:]])
            except ValueError:
                block = None
    return out


def read_dat_displacements(path):
    """{time: {node: (u1, u2)}} of the 'displacements' blocks of a .dat file
    (of all sets printed at a time; a node printed twice: the last)."""
    return {t: {int(r[0]): (r[1], r[2]) for r in rows if len(r) >= 3}
            for t, rows in _dat_blocks(path, "displacements (vx,vy,vz)").items()}


def read_dat_temperatures(path):
    """{time: {node: T}} of the 'temperatures' blocks of a .dat file
    (*NODE PRINT NT; a node printed twice: the last)."""
    return {t: {int(r[0]): r[1] for r in rows if len(r) == 2}
            for t, rows in _dat_blocks(path, "temperatures for set").items()}


def read_dat_stresses(path):
    """{time: {element: {point: (sxx, syy, szz, sxy, sxz, syz)}}} of the
    'stresses' blocks of a .dat file (*EL PRINT S: one line per element
    and integration point)."""
    out = {}
    for t, rows in _dat_blocks(path, "stresses (elem, integ.pnt.,").items():
        block = out[t] = {}
        for r in rows:                      # a point printed twice: the last
            if len(r) == 8:
                block.setdefault(int(r[0]), {})[int(r[1])] = tuple(r[2:8])
    return out


def read_dat_contact_stresses(path):
    """{time: [(element, face, pressure)]} of the 'contact stress' blocks
    of a .dat file (*CONTACT PRINT CSTRESS: one line per point of the
    slave face's intersections with the master faces; the face is the
    expanded 3D element's)."""
    return {t: [(int(r[0]), int(r[1]), r[2]) for r in rows if len(r) == 5]
            for t, rows in _dat_blocks(path, "contact stress (slave element+face,").items()}


def read_dat_slave_node_contact(path):
    """{time: {slave node: (pressure, tang1, tang2)}} of the node-to-surface
    'contact stress (slave node,press,tang1,tang2)' blocks of a .dat file
    (*CONTACT PRINT CSTR of a NODE TO SURFACE pair: one line per slave node
    in contact; for 2D elements the nodes are the expanded ones, which
    map_expanded_nodes brings back)."""
    return {t: {int(r[0]): (r[1], r[2], r[3]) for r in rows if len(r) == 4}
            for t, rows in _dat_blocks(path, "contact stress (slave node,").items()}


def read_dat_set_forces(path):
    """{set: {time: {node: (fx, fy)}}} of the 'forces (fx,fy,fz) for set
    NAME and time T' blocks of a .dat file (*NODE PRINT RF, one block per
    set and time; for 2D elements CalculiX prints the deck's nodes, each
    with the sum of its expanded nodes' forces)."""
    title = re.compile(r"\s*forces \(fx,fy,fz\) for set (\S+) and time\s+(\S+)")
    out, block = {}, None
    with open(path, errors="replace") as f:
        for line in f:
            m = title.match(line)
            if m:
                block = out.setdefault(m.group(1).upper(), {}).setdefault(float(m.group(2)), {})
                continue
            parts = line.split()
            if block is None or not parts:
                continue
            if not parts[0].isdigit():
                block = None
                continue
            block[int(parts[0])] = (float(parts[1]), float(parts[2]))
    return out


# --- .frd ------------------------------------------------------------------

def _frd_number(text):
    """A field of a .frd record; a blank field is 0, as Fortran reads it."""
    text = text.strip()
    return float(text) if text else 0.0


def _frd_lines(path):
    with open(path, "rb") as f:
        data = f.read()
    if b"\0" in data:
        raise ValueError(f"{path}: a binary .frd is not read")
    return data.decode("latin-1").splitlines()


def _frd_key(raw):
    # data records start with " -n" (the node number may follow without a
    # blank), header records with a counter and a name: "    1PSTEP"
    return raw[:3].strip() if raw[:2] == " -" else (raw.split() or [""])[0]


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
    for no, raw in enumerate(_frd_lines(path), 1):
        key = _frd_key(raw)
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


def read_frd_mesh(path):
    """The mesh of a .frd: ({node: (x, y, z)} of its node block (2C),
    {element: [nodes]} of its element block (3C)), each empty when the
    file has none. The blocks' format flag (column 74: 0 short, 1 long)
    gives the width of the numbers (5 or 10). A ValueError names a line
    that cannot be read."""
    xyz, elements = {}, {}
    part, width, current = None, 10, None
    for no, raw in enumerate(_frd_lines(path), 1):
        key = _frd_key(raw)
        try:
            if key in ("2C", "3C"):
                part, width = key, (5 if raw[73:74] == "0" else 10)
            elif key == "-3" or (part and key and not key.startswith("-")):
                part = None
            elif part == "2C" and key == "-1":
                vals = raw[3 + width:]
                xyz[int(raw[3:3 + width])] = tuple(_frd_number(vals[12 * k:12 * k + 12]) for k in range(3))
            elif part == "3C" and key == "-1":
                current = elements[int(raw[3:3 + width])] = []
            elif part == "3C" and key == "-2":
                body = raw[3:].rstrip()
                current.extend(int(body[k:k + width]) for k in range(0, len(body), width))
        except (ValueError, IndexError, TypeError, AttributeError) as e:
            raise ValueError(f"{path}:{no}: cannot read the record ({e})") from None
    return xyz, elements


def frd_by_time(datasets):
    """{time: {node: (d1, d2)}} of read_frd_displacements' blocks (the
    last block of a time wins), the in-plane components."""
    out = {}
    for d in datasets:
        out[d["time"]] = {n: v[:2] for n, v in d["u"].items()}
    return out


# --- the deck's mesh ---------------------------------------------------------

def _element_size(etype):
    """Nodes per element of the types whose name says it (CPE8R: 8, T2D2:
    2, C3D20: 20), else None (the data line's trailing comma decides)."""
    m = re.match(r"(CPS|CPE|CAX|C3D|T2D|T3D)(\d+)", etype)
    return int(m.group(2)) if m else None


def _numbers(line):
    return [f.strip() for f in line.split(",")]


def read_deck_mesh(path, seen=None):
    """The nodes {id: (x, y)} and elements {id: (type, [nodes])} of a deck
    and the files it includes (missing includes are skipped). Blank
    coordinates are 0. An element's nodes may go on over further lines:
    up to the count its type names, else while a line ends in a comma.
    Data lines that are not numbers are skipped (the deck has run through
    cfe2d, which checks them)."""
    seen = seen if seen is not None else set()
    nodes, elements = {}, {}
    if path in seen or not os.path.isfile(path):
        return nodes, elements
    seen.add(path)
    mode, etype, pending = None, "", None
    with open(path, errors="replace") as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                head = s.upper().replace(" ", "")
                mode, pending = None, None
                if head.startswith("*INCLUDE"):
                    m = re.search(r"INPUT=([^,]+)", s, re.I)
                    if m:
                        n2, e2 = read_deck_mesh(os.path.join(os.path.dirname(path), m.group(1).strip()), seen)
                        nodes.update(n2)
                        elements.update(e2)
                elif head.split(",")[0] == "*NODE" and "INPUT=" not in head:
                    mode = "node"
                elif head.split(",")[0] == "*ELEMENT" and "INPUT=" not in head:
                    m = re.search(r"TYPE=([A-Z0-9]+)", head)
                    mode, etype = "element", (m.group(1) if m else "")
                continue
            try:
                pending = _mesh_line(s, mode, etype, pending, nodes, elements)
            except (ValueError, IndexError):
                pending = None          # not a line this reader understands: skipped
    return nodes, elements


def _mesh_line(s, mode, etype, pending, nodes, elements):
    """Read one data line of *NODE or *ELEMENT into nodes or elements;
    returns the element whose nodes go on over the next line (or None)."""
    fields = _numbers(s)
    if mode == "node":
        vals = [float(v.lower().replace("d", "e")) if v else 0.0 for v in fields[1:3]]
        nodes[int(fields[0])] = tuple(vals + [0.0] * (2 - len(vals)))
    elif mode == "element":
        ids = [int(v) for v in fields if v]
        if pending is None:
            pending = [ids[0], ids[1:]]
            elements[ids[0]] = (etype, pending[1])
        else:
            pending[1].extend(ids)
        size = _element_size(etype)
        if (len(pending[1]) >= size) if size else not s.endswith(","):
            pending = None
    return pending


# --- expanded nodes back to 2D nodes ----------------------------------------

def _positions(xy2d, candidates):
    """The distinct (x, y) of the candidate nodes: (array (m, 2), list of
    the nodes at each); nodes closer than 1e-9 of the model's size share
    a position."""
    ids = sorted(candidates)
    pts = np.array([xy2d[n] for n in ids], dtype=float).reshape(-1, 2)
    size = float(np.ptp(pts, axis=0).max()) if len(pts) else 0.0
    tol = 1e-9 * size
    where, nodes = [], []
    for n, p in zip(ids, pts):
        for j, q in enumerate(where):
            if abs(p[0] - q[0]) <= tol and abs(p[1] - q[1]) <= tol:
                nodes[j].append(n)
                break
        else:
            where.append(p)
            nodes.append([n])
    return np.array(where).reshape(-1, 2), nodes, size


def _nearest(points, where):
    """Index of the nearest row of where and its distance, for each point."""
    index = np.zeros(len(points), dtype=int)
    dist = np.zeros(len(points))
    for a in range(0, len(points), 512):
        d = np.linalg.norm(points[a:a + 512, None, :] - where[None, :, :], axis=2)
        index[a:a + 512] = d.argmin(axis=1)
        dist[a:a + 512] = d.min(axis=1)
    return index, dist


def map_expanded_nodes(frd_xyz, frd_elements, xy2d, elements2d):
    """Which expanded nodes of a .frd stand for which 2D node.

    frd_xyz {node: (x, y, z)}, frd_elements {element: [nodes]} (the .frd's
    2C and 3C blocks); xy2d {node: (x, y)} and elements2d {element:
    [nodes]}: the 2D model (its elements' nodes are the candidates, so a
    node in no element, as a pre-tension's reference node, takes none).

    Each expanded node goes to the nearest candidate position in (x, y)
    when it is nearer than half the distance from there to the next
    position; a position keeps its nodes when their mean (x, y) is the
    position (to 1e-4 of the model's size: the .frd prints 6 digits).
    Where two 2D nodes share a position (a pre-tension's copy of a cut
    node), each takes the expanded nodes of its own elements (the .frd
    keeps the deck's element numbers; expanded nodes there in none of
    them are left out); if that does not split them into disjoint sets,
    none of them is mapped.

    Returns (groups {2D node: [expanded nodes]}, coincident [2D nodes not
    mapped because they share a position], off [2D nodes whose expanded
    nodes do not centre on them])."""
    candidates = {n for conn in elements2d.values() for n in conn if n in xy2d}
    where, at, size = _positions(xy2d, candidates)
    groups, coincident, off = {}, [], []
    if not len(where) or not frd_xyz:
        return groups, coincident, off
    ids = sorted(frd_xyz)
    pts = np.array([frd_xyz[q][:2] for q in ids], dtype=float)
    index, dist = _nearest(pts, where)
    if len(where) > 1:
        gap = np.array([np.sort(np.linalg.norm(where - w, axis=1))[1] for w in where])
    else:
        gap = np.full(1, np.inf)
    near = {}
    for q, j, d in zip(ids, index, dist):
        if d <= 0.5 * gap[j]:
            near.setdefault(int(j), []).append(q)
    owners = {}
    for e, conn in elements2d.items():
        for n in conn:
            owners.setdefault(n, set()).add(e)
    for j, qs in near.items():
        mean = np.array([frd_xyz[q][:2] for q in qs], dtype=float).mean(axis=0)
        if np.abs(mean - where[j]).max() > 1e-4 * size:
            off += at[j]
            continue
        if len(at[j]) == 1:
            groups[at[j][0]] = sorted(qs)
            continue
        split = {n: sorted({q for e in owners.get(n, ()) for q in frd_elements.get(e, ()) if q in qs})
                 for n in at[j]}
        taken = [q for s in split.values() for q in s]
        if all(split.values()) and len(taken) == len(set(taken)):
            groups.update(split)
        else:
            coincident += at[j]
    return groups, sorted(coincident), sorted(off)


def expanded_displacements(datasets, groups):
    """{time: {2D node: (u1, u2)}}: the mean in-plane displacement of each
    2D node's expanded nodes (map_expanded_nodes' groups) in the .frd's
    displacement blocks (read_frd_displacements; the last block of a time
    wins); a node none of whose expanded nodes a block holds is left out."""
    out = {}
    for d in datasets:
        block = out[d["time"]] = {}
        for n, qs in groups.items():
            vals = [d["u"][q][:2] for q in qs if q in d["u"]]
            if vals:
                block[n] = tuple(float(v) for v in np.mean(vals, axis=0))
    return out


# --- integration points and faces ---------------------------------------------

def stress_layers(n3, n2):
    """For each of the n2 integration points of a 2D element, the points
    (1-based) of CalculiX's expanded element with n3 points whose mean
    stands for it, or None when n3 is not a multiple of n2.

    CalculiX numbers the points of the expanded element layer by layer
    through the thickness, each layer in the order of the 2D element's
    points: in its .dat the out-of-plane shears (sxz, syz) of the first
    layer are those of the last with the sign changed and vanish in the
    middle one (CAX8 -> C3D20, 27 points = 3 layers of 9), and the layers'
    in-plane values follow the 2D points. With an odd number of layers the
    middle one lies in the 2D element's plane; with an even number (C3D20R
    or C3D8: 2 layers of 4) the mean of the two middle layers, symmetric
    about it, stands for it. n3 == n2 (an element CalculiX did not
    expand) maps point k to point k."""
    if n2 <= 0 or n3 % n2:
        return None
    layers = n3 // n2
    mid = [layers // 2] if layers % 2 else [layers // 2 - 1, layers // 2]
    return [[m * n2 + k for m in mid] for k in range(1, n2 + 1)]


def deck_face_polyline(etype, conn, face):
    """The nodes along face `face` (1-based, S1..S4 of the 2D element) of a
    2D element: its two corners, with the midside node between them for
    quadratic elements. None for a face the element does not have."""
    size = _element_size(etype) or len(conn)
    corners = 3 if size in (3, 6) else 4
    if not 1 <= face <= corners or len(conn) < corners:
        return None
    a, b = conn[face - 1], conn[face % corners]
    if len(conn) >= 2 * corners:
        return [a, conn[corners + face - 1], b]
    return [a, b]


def _segment_distance(p, a, b):
    ab = b - a
    t = 0.0 if not ab.any() else float(np.clip(np.dot(p - a, ab) / np.dot(ab, ab), 0.0, 1.0))
    return float(np.linalg.norm(p - (a + t * ab)))


def nearest_face(point, faces):
    """The key of the face (a polyline of (x, y) points) nearest to point
    and its distance over that face's length, from {key: polyline}; (None,
    inf) when there are none."""
    best, rel = None, np.inf
    p = np.asarray(point, dtype=float)
    for key, line in faces.items():
        line = np.asarray(line, dtype=float)
        length = sum(float(np.linalg.norm(line[k + 1] - line[k])) for k in range(len(line) - 1))
        d = min(_segment_distance(p, line[k], line[k + 1]) for k in range(len(line) - 1))
        r = d / length if length > 0 else np.inf
        if r < rel:
            best, rel = key, r
    return best, rel

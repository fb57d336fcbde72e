"""Read the MSH 2.2 result files that cfe2d writes (<job>.msh): binary, as
cfe2d writes them, or ASCII (older files, or a file gmsh saved again).

Views are kept by name, whatever they are: "Displacement", "Reaction
force", "S11" ... "Mises", "Contact pressure" and, when the model has
friction, "CSHEAR" (the contact shear traction at the same nodes), and the
element views. ``node_view("CSHEAR", k)`` reads the shear of time step k."""
import numpy as np

__all__ = ["read_msh"]


class MshResults:
    def __init__(self):
        self.node_ids = None       # (n,)
        self.xy = None             # (n, 2)
        self.elements = []         # lists of node ids
        self.element_ids = []      # the elements' numbers (the deck's), aligned with elements
        self.element_types = []    # their gmsh types, aligned with elements
        self.views = {}            # name -> list of (time, ids (k,), values (k, ncomp))

    def node_view(self, name, step):
        """Values of view `name` at time-step index `step` (0-based) as an
        array aligned with node_ids (NaN where absent)."""
        time, ids, vals = self.views[name][step]
        out = np.full((len(self.node_ids), vals.shape[1]), np.nan)
        order = np.argsort(self.node_ids)
        out[order[np.searchsorted(self.node_ids, ids, sorter=order)]] = vals
        return time, out

    def triangles(self):
        """Node indices of a triangulation of the surface elements (quads
        split; trusses, springs and point masses left out)."""
        index = {n: i for i, n in enumerate(self.node_ids)}
        tris = []
        for conn, etype in zip(self.elements, self.element_types):
            if etype not in _SURFACE:
                continue
            c = [index[n] for n in conn]
            tris.append(c[:3])
            if len(c) == 4:
                tris.append([c[0], c[2], c[3]])
        return np.array(tris)


# nodes of the gmsh element types cfe2d writes (line, triangle, quadrangle,
# second-order line, triangle and quadrangle, point)
_NODES = {1: 2, 2: 3, 3: 4, 8: 3, 9: 6, 10: 9, 16: 8, 15: 1}
_SURFACE = {2, 3, 9, 10, 16}


class _Reader:
    """Lines and binary blocks of one file, read as bytes."""

    def __init__(self, data):
        self.data, self.pos = data, 0

    def line(self):
        end = self.data.index(b"\n", self.pos)
        text = self.data[self.pos:end].decode()
        self.pos = end + 1
        return text.strip()

    def array(self, dtype, count):
        a = np.frombuffer(self.data, dtype=dtype, count=count, offset=self.pos)
        self.pos += a.nbytes
        return a

    def records(self, nreal, count):
        """count records of one int32 and nreal float64 each."""
        rec = np.dtype([("id", "<i4"), ("v", "<f8", (nreal,))])
        a = np.frombuffer(self.data, dtype=rec, count=count, offset=self.pos)
        self.pos += a.nbytes
        return a["id"].astype(int), a["v"]

    def done(self):
        return self.pos >= len(self.data)


def _view_header(rd):
    nstr = int(rd.line())
    name = rd.line().strip('"')
    for _ in range(nstr - 1):
        rd.line()
    nreal = int(rd.line())
    time = float(rd.line())
    for _ in range(nreal - 1):
        rd.line()
    nint_ = int(rd.line())
    ints = [int(rd.line()) for _ in range(nint_)]
    return name, time, ints[1], ints[2]


def _binary_elements(rd, n, r):
    read = 0
    while read < n:
        etype, count, ntags = rd.array("<i4", 3)
        nn = _NODES[int(etype)]
        conn = rd.array("<i4", int(count) * (1 + int(ntags) + nn)).reshape(int(count), -1)
        r.elements.extend(conn[:, 1 + int(ntags):].tolist())
        r.element_ids.extend(int(k) for k in conn[:, 0])
        r.element_types.extend([int(etype)] * int(count))
        read += int(count)


def read_msh(path):
    with open(path, "rb") as f:
        rd = _Reader(f.read())
    r = MshResults()
    binary = False
    while not rd.done():
        line = rd.line()
        if line == "$MeshFormat":
            binary = rd.line().split()[1] == "1"
            if binary:
                one = rd.array("<i4", 1)[0]
                assert one == 1, "big-endian MSH files are not read here"
                rd.line()
        elif line == "$Nodes":
            n = int(rd.line())
            if binary:
                ids, xyz = rd.records(3, n)
            else:
                w = np.array([rd.line().split() for _ in range(n)], dtype=float)
                ids, xyz = w[:, 0].astype(int), w[:, 1:4]
            r.node_ids, r.xy = ids, np.array(xyz[:, :2])
        elif line == "$Elements":
            n = int(rd.line())
            if binary:
                _binary_elements(rd, n, r)
            else:
                for _ in range(n):
                    w = [int(v) for v in rd.line().split()]
                    r.elements.append(w[3 + w[2]:])
                    r.element_ids.append(w[0])
                    r.element_types.append(w[1])
        elif line in ("$NodeData", "$ElementData"):
            name, time, ncomp, count = _view_header(rd)
            if binary:
                ids, vals = rd.records(ncomp, count)
            else:
                w = np.array([rd.line().split() for _ in range(count)], dtype=float).reshape(count, ncomp + 1)
                ids, vals = w[:, 0].astype(int), w[:, 1:]
            r.views.setdefault(name, []).append((time, ids, vals))
    return r

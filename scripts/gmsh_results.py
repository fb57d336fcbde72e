"""Read the MSH 2.2 ASCII result files that cfe2d writes (<job>.msh)."""
import numpy as np

__all__ = ["read_msh"]


class MshResults:
    def __init__(self):
        self.node_ids = None       # (n,)
        self.xy = None             # (n, 2)
        self.elements = []         # lists of node ids
        self.views = {}            # name -> list of (time, {id: values})

    def node_view(self, name, step):
        """Values of view `name` at time-step index `step` (0-based) as an
        array aligned with node_ids (NaN where absent)."""
        time, data = self.views[name][step]
        ncomp = len(next(iter(data.values())))
        out = np.full((len(self.node_ids), ncomp), np.nan)
        index = {n: i for i, n in enumerate(self.node_ids)}
        for n, v in data.items():
            out[index[n]] = v
        return time, out

    def triangles(self):
        """Node indices of a triangulation of the elements (quads split)."""
        index = {n: i for i, n in enumerate(self.node_ids)}
        tris = []
        for conn in self.elements:
            c = [index[n] for n in conn]
            tris.append(c[:3])
            if len(c) == 4:
                tris.append([c[0], c[2], c[3]])
        return np.array(tris)


def read_msh(path):
    r = MshResults()
    with open(path) as f:
        lines = iter(f.read().splitlines())
    for line in lines:
        if line == "$Nodes":
            n = int(next(lines))
            ids, xy = np.empty(n, dtype=int), np.empty((n, 2))
            for i in range(n):
                w = next(lines).split()
                ids[i], xy[i] = int(w[0]), (float(w[1]), float(w[2]))
            r.node_ids, r.xy = ids, xy
        elif line == "$Elements":
            n = int(next(lines))
            for _ in range(n):
                w = [int(v) for v in next(lines).split()]
                ntags = w[2]
                r.elements.append(w[3 + ntags:])
        elif line in ("$NodeData", "$ElementData"):
            nstr = int(next(lines))
            name = next(lines).strip('"')
            for _ in range(nstr - 1):
                next(lines)
            nreal = int(next(lines))
            time = float(next(lines))
            for _ in range(nreal - 1):
                next(lines)
            nint_ = int(next(lines))
            ints = [int(next(lines)) for _ in range(nint_)]
            count = ints[2]
            data = {}
            for _ in range(count):
                w = next(lines).split()
                data[int(w[0])] = [float(v) for v in w[1:]]
            key = name if line == "$NodeData" else name
            r.views.setdefault(key, []).append((time, data))
    return r

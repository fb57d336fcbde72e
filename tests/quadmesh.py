"""Structured meshes of every element shape for the element tests: a map
(s, t) -> (x, y) of the parameter rectangle [0, nx] x [0, ny] is meshed
with 3-, 4-, 6- or 8-node elements (Abaqus node order, counter-clockwise
for a map that keeps orientation). Mid-side nodes sit on the mapped
curve (curved edges for a curved map) or, with straight=True, at the
midpoints of the element edges."""

SHAPES = {"T3": 3, "Q4": 4, "T6": 6, "Q8": 8}
# faces of each shape: corner pairs (local indices), Abaqus order
FACES = {3: [(0, 1), (1, 2), (2, 0)], 6: [(0, 1), (1, 2), (2, 0)],
         4: [(0, 1), (1, 2), (2, 3), (3, 0)], 8: [(0, 1), (1, 2), (2, 3), (3, 0)]}


class Mesh:
    def __init__(self, shape, nx, ny, xy, straight=False, first_node=1, first_elem=1):
        self.shape, self.nx, self.ny = shape, nx, ny
        self.nodes, self.index = {}, {}        # id -> (x, y); fine index (2i, 2j) -> id
        self.elements = []                     # node id tuples
        self._next = first_node
        self.first_elem = first_elem
        nn = SHAPES[shape]
        for j in range(ny):
            for i in range(nx):
                c = [(2 * i, 2 * j), (2 * i + 2, 2 * j), (2 * i + 2, 2 * j + 2), (2 * i, 2 * j + 2)]
                if nn in (4, 8):
                    tris = [c]
                elif (i + j) % 2:
                    tris = [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
                else:
                    tris = [[c[0], c[1], c[3]], [c[1], c[2], c[3]]]
                for corners in tris:
                    ids = [self._node(k, xy, None) for k in corners]
                    if nn in (6, 8):
                        for a, b in FACES[nn]:
                            ka, kb = corners[a], corners[b]
                            mid = ((ka[0] + kb[0]) // 2, (ka[1] + kb[1]) // 2)
                            ids.append(self._node(mid, xy, (ids[a], ids[b]) if straight else None))
                    self.elements.append(tuple(ids))

    def _node(self, k, xy, ends):
        if k not in self.index:
            if ends is None:
                p = xy(k[0] / 2.0, k[1] / 2.0)
            else:
                (xa, ya), (xb, yb) = self.nodes[ends[0]], self.nodes[ends[1]]
                p = (0.5 * (xa + xb), 0.5 * (ya + yb))
            self.index[k] = self._next
            self.nodes[self._next] = (float(p[0]), float(p[1]))
            self._next += 1
        return self.index[k]

    def side(self, name):
        """Node ids on a side of the parameter rectangle: left (s = 0),
        right (s = nx), bottom (t = 0), top (t = ny)."""
        test = {"left": lambda i, j: i == 0, "right": lambda i, j: i == 2 * self.nx,
                "bottom": lambda i, j: j == 0, "top": lambda i, j: j == 2 * self.ny}[name]
        return [n for k, n in sorted(self.index.items()) if test(*k)]

    def boundary(self):
        return sorted(set(self.side("left") + self.side("right") + self.side("bottom") + self.side("top")))

    def faces(self, name):
        """(element id, face number) of the element faces on a side."""
        on = set(self.side(name))
        out = []
        for e, conn in enumerate(self.elements):
            for k, (a, b) in enumerate(FACES[len(conn)]):
                if conn[a] in on and conn[b] in on:
                    out.append((self.first_elem + e, k + 1))
        return out

    def node_lines(self):
        return "".join(f"{n}, {x:.17g}, {y:.17g}\n" for n, (x, y) in self.nodes.items())

    def element_lines(self):
        return "".join(f"{self.first_elem + e}, " + ", ".join(map(str, c)) + "\n"
                       for e, c in enumerate(self.elements))

    def element_card(self, etype, elset):
        return f"*ELEMENT, TYPE={etype}, ELSET={elset}\n" + self.element_lines()

    def surface_card(self, name, side):
        return f"*SURFACE, NAME={name}\n" + "".join(f"{e}, S{k}\n" for e, k in self.faces(side))


def etype(shape, state):
    """Abaqus element name of a shape in a stress state ('S', 'E', 'AX')."""
    base = {"T3": "3", "Q4": "4", "T6": "6", "Q8": "8"}[shape]
    return {"S": "CPS", "E": "CPE", "AX": "CAX"}[state] + base

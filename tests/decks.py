"""Deck generators for the verification tests: structured and distorted
meshes written as keyword decks."""


def grid(nx, ny, x0, x1, y0, y1, distort=0.0, first_node=1):
    """Nodes of a (nx+1) x (ny+1) grid, interior nodes shifted by a fixed
    pseudo-random pattern of relative size `distort`."""
    nodes = {}
    hx, hy = (x1 - x0) / nx, (y1 - y0) / ny
    nid = first_node
    ids = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = x0 + i * hx, y0 + j * hy
            if 0 < i < nx and 0 < j < ny and distort:
                x += distort * hx * (((i * 7 + j * 3) % 5) / 4.0 - 0.5)
                y += distort * hy * (((i * 3 + j * 5) % 7) / 6.0 - 0.5)
            nodes[nid] = (x, y)
            ids[i, j] = nid
            nid += 1
    quads = []
    for j in range(ny):
        for i in range(nx):
            quads.append((ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]))
    return nodes, ids, quads


def node_lines(nodes):
    return "".join(f"{n}, {x:.17g}, {y:.17g}\n" for n, (x, y) in nodes.items())


def quad_lines(quads, first=1):
    return "".join(f"{first + k}, {a}, {b}, {c}, {d}\n" for k, (a, b, c, d) in enumerate(quads))


def tri_lines(quads, first=1):
    """Each quad split into two triangles along alternating diagonals."""
    out, k = [], first
    for q, (a, b, c, d) in enumerate(quads):
        if q % 2:
            tris = [(a, b, c), (a, c, d)]
        else:
            tris = [(a, b, d), (b, c, d)]
        for t in tris:
            out.append(f"{k}, {t[0]}, {t[1]}, {t[2]}\n")
            k += 1
    return "".join(out)

"""Read a cfe2d listing (<job>.out) into Python structures.

A listing is a sequence of blocks. A block starts with a line
``--- NAME key=value ...``, followed by a line of column names and then
rows; increments are framed by ``=== INCREMENT key=value ... ===`` and
``=== END INCREMENT``.

    >>> lst = read_listing("job.out")
    >>> inc = lst.increments[-1]
    >>> inc.block("NODE U", set="TOP")["U2"]

Contact tables: the state of a coupling point is OPEN, or when closed
CLOSED (frictionless pair) or STICK / SLIP (frictional pair, whose tables
also have the columns shear_force, shear, slip, slip_inc, and on the master
side shear_force, shear; its summary shear_total). ``is_closed(state)`` and
``closed_mask(block)`` say which rows are closed whatever the pair.
"""
from __future__ import annotations

import shlex
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Block", "Increment", "Listing", "read_listing", "parse_listing", "CLOSED_STATES", "is_closed",
           "closed_mask"]

# the states of a closed coupling point: frictionless, frictional sticking, sliding
CLOSED_STATES = ("CLOSED", "STICK", "SLIP")


def is_closed(state):
    """Is a contact row with this state (listing or contact table) closed?"""
    return state.strip() in CLOSED_STATES


def closed_mask(block):
    """Boolean array: the closed rows of a CONTACT SLAVE block."""
    return np.array([is_closed(s) for s in block["state"]], dtype=bool)


def _keyvals(words):
    out = {}
    for w in words:
        if "=" in w:
            k, v = w.split("=", 1)
            out[k] = v
    return out


def _number(s):
    try:
        return float(s)
    except ValueError:
        return s


@dataclass
class Block:
    name: str
    attrs: dict
    columns: list
    rows: list = field(default_factory=list)

    def __getitem__(self, col):
        """Column as a numpy array (numbers) or a list (words)."""
        j = self.columns.index(col)
        vals = [r[j] for r in self.rows]
        if all(isinstance(v, float) for v in vals):
            return np.array(vals, dtype=float)
        return vals

    def __len__(self):
        return len(self.rows)

    def as_dict(self):
        """First column -> remaining columns, for item/value blocks."""
        return {r[0]: (r[1] if len(r) == 2 else r[1:]) for r in self.rows}


@dataclass
class Increment:
    attrs: dict
    blocks: list = field(default_factory=list)

    @property
    def step(self):
        return int(self.attrs["step"])

    @property
    def number(self):
        return int(self.attrs["increment"])

    @property
    def time(self):
        return float(self.attrs["total_time"])

    def block(self, name, **attrs):
        for b in self.blocks:
            if b.name == name and all(b.attrs.get(k) == str(v) for k, v in attrs.items()):
                return b
        raise KeyError(f"no block {name} {attrs} in increment {self.attrs}")

    def has(self, name, **attrs):
        try:
            self.block(name, **attrs)
            return True
        except KeyError:
            return False


@dataclass
class Listing:
    header: list
    increments: list


def parse_listing(text):
    header, increments = [], []
    current = None  # the increment being read, or None in the header part
    block = None
    expect_columns = False
    for line in text.splitlines():
        if line.startswith("=== INCREMENT"):
            current = Increment(_keyvals(line.strip("= ").split()))
            increments.append(current)
            block = None
            continue
        if line.startswith("=== END INCREMENT"):
            current, block = None, None
            continue
        if line.startswith("--- "):
            words = line[4:].split()
            # block names are the upper-case words before the first key=value
            name = []
            for w in words:
                if "=" in w or w.startswith("("):
                    break
                name.append(w)
            block = Block(" ".join(name), _keyvals(words), [])
            (current.blocks if current is not None else header).append(block)
            expect_columns = True
            continue
        if block is None or not line.strip():
            continue
        if expect_columns:
            block.columns = line.split()
            expect_columns = False
            continue
        parts = line.split()
        if block.columns and block.columns[0] == "item":
            block.rows.append([parts[0], " ".join(parts[1:])])
        else:
            block.rows.append([_number(p) for p in parts])
    return Listing(header, increments)


def read_listing(path):
    with open(path) as f:
        return parse_listing(f.read())

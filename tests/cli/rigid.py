"""Rigid transforms for the CLI tests' Python parts, in hexcal's conventions
(docs/conventions.md): a pose is (t, R) with R = Rz(q3) Ry(q2) Rx(q1), angles
in degrees; comp(a_from_b, b_from_c) is a_from_c. Plain lists, no numpy."""
import math


def mm(a, b): return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def mv(a, v): return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]
def tr(a): return [list(r) for r in zip(*a)]


def rot(q):  # Rz(q3) Ry(q2) Rx(q1), degrees
    a, b, c = [math.radians(x) for x in q]
    rx = [[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]]
    ry = [[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]]
    rz = [[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]]
    return mm(rz, mm(ry, rx))


def pose(v): return (v[:3], rot(v[3:]))
def comp(a, b): return ([x + y for x, y in zip(mv(a[1], b[0]), a[0])], mm(a[1], b[1]))
def inv(a): return ([-x for x in mv(tr(a[1]), a[0])], tr(a[1]))
def apply(p, x): return [u + v for u, v in zip(mv(p[1], x), p[0])]


def vec(p):
    t, r = p
    return t + [math.degrees(math.atan2(r[2][1], r[2][2])), math.degrees(math.asin(-r[2][0])),
                math.degrees(math.atan2(r[1][0], r[0][0]))]

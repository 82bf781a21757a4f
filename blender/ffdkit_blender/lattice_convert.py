"""Blender Lattice objects <-> ffdkit lattices, exactly.

Blender's Lattice modifier (lattice_deform.cc) moves a point by a displacement field: in the
lattice object's space, with the rest grid at ``f + i * d`` per axis (i = 0..n-1), a point at
parameter ``u = (x - f) / d`` moves by

    D(u) = sum_r K_r(frac(u)) * delta[clamp(floor(u) - 1 + r, 0, n - 1)],   r = 0..3,

(tensor product over the three axes) where ``delta`` are the lattice points' moves from the grid
and ``K`` the four weights of the axis's interpolation (Blender's key_curve_position_weights in
key.cc: KEY_LINEAR, KEY_CARDINAL with tension 0.71, KEY_CATMULL_ROM (tension 0.5), KEY_BSPLINE,
the uniform cubic B-spline). Because the indices are clamped, the field is a piecewise cubic on
the unit cells between u = -1 and u = n, constant beyond.

KEY_LINEAR is the degree-1 B-spline on the grid (constant beyond the end points). The three cubic
interpolations give C1 piecewise cubics, so their field lies in the space of cubic splines
with double knots at the integers -1..n (2n + 4 functions per axis): on each cell the two inner
Bezier points of the field are B-spline coefficients, and the ends add one each. An ffdkit
lattice with those knots (AxisBasis.bsplineWithKnots(3, ...)), its rest points at the Greville
abscissae (so that rest = identity), its control points the rest plus the converted moves, and
the ClampEdge outside policy (outside points move with the border: Blender's constant field)
deforms exactly as the modifier does, up to Blender's float32 arithmetic. Blender's weights are
used here with Blender's own float32 constants.

The reverse direction converts an ffdkit box lattice whose axes are linear (degree-1 B-splines on
uniform knots, or a two-point Bernstein axis) or have this double-knot form and lie in the image
of one of Blender's interpolations; anything else raises NotRepresentable saying why.
"""

import numpy as np

KINDS = ("KEY_LINEAR", "KEY_CARDINAL", "KEY_CATMULL_ROM", "KEY_BSPLINE")


class NotRepresentable(ValueError):
    """An ffdkit lattice that has no exact Blender Lattice equivalent; the message says why."""


def _f32(value):
    return float(np.float32(value))


def blender_weights(kind):
    """Power-form coefficients of Blender's four weights of one cell: K[r, p] is the t^p
    coefficient of weight r (for the points floor(u)-1 .. floor(u)+2), as key.cc computes them
    (its float32 constants)."""
    if kind == "KEY_LINEAR":
        return np.array([[0, 0, 0, 0], [1, -1, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0]], dtype=np.float64)
    if kind in ("KEY_CARDINAL", "KEY_CATMULL_ROM"):
        fc = _f32(0.71) if kind == "KEY_CARDINAL" else 0.5
        return np.array([
            [0, -fc, 2 * fc, -fc],
            [1, 0, fc - 3, 2 - fc],
            [0, fc, 3 - 2 * fc, fc - 2],
            [0, 0, -fc, fc]], dtype=np.float64)
    if kind == "KEY_BSPLINE":
        sixth, two_thirds = _f32(0.16666666), _f32(0.66666666)
        return np.array([
            [sixth, -0.5, 0.5, -sixth],
            [two_thirds, 0, -1, 0.5],
            [sixth, 0.5, 0.5, -0.5],
            [0, 0, 0, sixth]], dtype=np.float64)
    raise ValueError("unknown interpolation %r (known: %s)" % (kind, ", ".join(KINDS)))


# Power basis (1, t, t^2, t^3) -> cubic Bernstein coefficients: b = P2B @ a.
_POWER_TO_BERNSTEIN = np.array([[1, 0, 0, 0], [1, 1 / 3, 0, 0], [1, 2 / 3, 1 / 3, 0], [1, 1, 1, 1]])


class AxisForm:
    """One axis of the ffdkit form of a Blender lattice axis with n points.

    Fields: degree, knots (parameter = Blender's point index), greville (rest coordinates, one per
    ffdkit control point), matrix (#ffdkit points x n: ffdkit coefficients from Blender's moves).
    """

    def __init__(self, kind, n):
        if n < 1:
            raise ValueError("a lattice axis needs >= 1 point, got %d" % n)
        if n == 1:  # Blender: the one point's move, everywhere along the axis
            self.degree = 1
            self.knots = np.array([-1.0, -1.0, 1.0, 1.0])
            self.matrix = np.ones((2, 1))
        elif kind == "KEY_LINEAR":  # only C0: the n points themselves, knots at the grid
            self.degree = 1
            self.knots = np.array([0.0] + [float(i) for i in range(n)] + [float(n - 1)])
            self.matrix = np.eye(n)
        else:
            bernstein = _POWER_TO_BERNSTEIN @ blender_weights(kind).T  # [bezier point k, weight r]
            cells = list(range(-1, n))  # the cell [c, c + 1] uses points c - 1 .. c + 2, clamped
            rows = []
            for position, cell in enumerate(cells):
                bezier = np.zeros((4, n))
                for r in range(4):
                    bezier[:, min(max(cell - 1 + r, 0), n - 1)] += bernstein[:, r]
                if position == 0:
                    rows.append(bezier[0])
                rows.extend([bezier[1], bezier[2]])
                if position == len(cells) - 1:
                    rows.append(bezier[3])
            self.degree = 3
            self.knots = np.array([-1.0] * 4 + [float(b) for b in range(0, n) for _ in range(2)] + [float(n)] * 4)
            self.matrix = np.array(rows)
        p = self.degree
        count = len(self.knots) - p - 1
        self.greville = np.array([self.knots[j + 1:j + p + 1].mean() for j in range(count)])


def _grid(a, b, c):
    """Flat (i fastest) grid of three coordinate lists, #a*#b*#c x 3."""
    w, v, u = np.meshgrid(c, b, a, indexing="ij")
    return np.column_stack([u.ravel(), v.ravel(), w.ravel()])


def _apply_axes(matrices, values, counts):
    """values: #points x 3 in Blender's flat order (u fastest) -> the tensor product of the axis
    matrices applied, in ffdkit's flat order (also u fastest)."""
    cube = values.reshape(counts[2], counts[1], counts[0], 3)
    out = np.einsum("Li,Kj,Jk,ijkc->LKJc", matrices[2], matrices[1], matrices[0], cube)
    return out.reshape(-1, 3)


def widget_model_from_blender(ffdkit, name, counts, kinds, origin, spacing, points, matrix_world):
    """The ffdkit widget model (one root lattice) that deforms as Blender's Lattice modifier.

    Args:
        ffdkit: the ffdkit package.
        name: the lattice widget's name.
        counts: (points_u, points_v, points_w).
        kinds: three interpolation names (KINDS).
        origin, spacing: the rest grid, per axis: point i at origin + i * spacing (lattice space).
        points: #points x 3, the lattice points' positions (co_deform), lattice space, u fastest.
        matrix_world: 4 x 4, the lattice object's world matrix (the model's world is Blender's).
    Returns:
        WidgetModel.
    """
    counts = [int(c) for c in counts]
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if points.shape[0] != counts[0] * counts[1] * counts[2]:
        raise ValueError("expected %d lattice points, got %d" % (counts[0] * counts[1] * counts[2], points.shape[0]))
    spacing = np.array([s if c > 1 else 1.0 for s, c in zip(spacing, counts)], dtype=np.float64)
    origin = np.asarray(origin, dtype=np.float64)
    axes = [AxisForm(kind, n) for kind, n in zip(kinds, counts)]
    rest = _grid(*(origin[a] + spacing[a] * np.arange(counts[a]) for a in range(3)))
    moves = (points - rest) / spacing  # in index units
    coefficients = _apply_axes([axis.matrix for axis in axes], moves, counts)
    ffdkit_rest = _grid(*(axis.greville for axis in axes))
    settings = ffdkit.widgets.LatticeSettings()
    settings.basis = [ffdkit.ffd.AxisBasis.bsplineWithKnots(axis.degree, axis.knots) for axis in axes]
    settings.outside = ffdkit.ffd.OutsidePolicy.clampEdge()
    to_lattice_space = np.eye(4)
    to_lattice_space[:3, :3] = np.diag(spacing)
    to_lattice_space[:3, 3] = origin
    model = ffdkit.widgets.WidgetModel()
    lattice = model.addLattice(name=name, counts=[len(axis.greville) for axis in axes],
                               frame=np.asarray(matrix_world, dtype=np.float64) @ to_lattice_space,
                               restPoints=ffdkit_rest, settings=settings)
    model.setControlPoints(lattice, ffdkit_rest + coefficients)
    return model


class BlenderLattice:
    """What a Blender Lattice object needs: counts, interpolation per axis, the deformed points
    (co_deform, lattice space, on Blender's default grid -0.5 (n-1) + i), the object's world
    matrix, and warnings about what differs (the outside of a lattice that leaves it alone)."""

    def __init__(self, counts, kinds, points, matrix_world, warnings):
        self.counts = counts
        self.kinds = kinds
        self.points = points
        self.matrix_world = matrix_world
        self.warnings = warnings


def blender_grid(counts):
    """Blender's rest grid of a new lattice (points_u/v/w set from Python): per axis the origin
    -0.5 (n - 1) and the spacing 1 (origin 0 for one point)."""
    return np.array([-0.5 * (n - 1) for n in counts]), np.ones(3)


def _axis_candidates(ffdkit, basis, count, axis_name):
    """[(Blender kind, Blender point count, AxisForm, first breakpoint, spacing)] an ffdkit axis
    may be; raises NotRepresentable when it can be none."""
    Kind = ffdkit.ffd.AxisBasis.Kind
    if basis.kind == Kind.Bernstein:
        if count == 2:
            return [("KEY_LINEAR", 2, AxisForm("KEY_LINEAR", 2), 0.0, 1.0)]
        raise NotRepresentable("axis %s: Bernstein of degree %d: Blender's lattice has no single-polynomial "
                               "basis (its interpolations are piecewise, over one cell per point)" % (axis_name, count - 1))
    if basis.kind == Kind.PeriodicBSpline:
        raise NotRepresentable("axis %s: periodic (cylindrical) B-spline: Blender's lattice is a box" % axis_name)
    knots = np.asarray(basis.knots, dtype=np.float64)
    if knots.size == 0:
        knots = np.asarray(ffdkit.ffd.clampedUniformKnots(count, basis.degree), dtype=np.float64)
    if basis.degree == 1:
        steps = np.diff(knots[1:-1])
        if np.allclose(steps, steps[0], rtol=1e-12, atol=0) and steps[0] > 0:
            return [("KEY_LINEAR", count, AxisForm("KEY_LINEAR", count), knots[1], steps[0])]
        raise NotRepresentable("axis %s: linear B-spline on non-uniform knots: Blender's grid is uniform" % axis_name)
    if basis.degree == 3 and count >= 6 and count % 2 == 0:
        n = (count - 4) // 2
        h = knots[6] - knots[4] if n > 1 else knots[-1] - knots[4]
        expected = AxisForm("KEY_BSPLINE", n).knots * h + (knots[4] if n > 1 else knots[4])
        if h > 0 and np.allclose(knots, expected, rtol=0, atol=1e-12 * max(1.0, np.abs(knots).max())):
            return [(kind, n, AxisForm(kind, n), knots[4], h) for kind in ("KEY_CATMULL_ROM", "KEY_CARDINAL", "KEY_BSPLINE")]
    raise NotRepresentable("axis %s: B-spline of degree %d on %s: Blender's lattice interpolations (linear, "
                           "cardinal, Catmull-Rom, B-spline) run over a uniform grid whose end points repeat, "
                           "and none of them gives this basis"
                           % (axis_name, basis.degree,
                              "clamped uniform knots (ffdkit's default)" if basis.knots.size == 0 else "its knots"))


def blender_lattice_from_model(ffdkit, model, lattice):
    """The Blender Lattice equal to an ffdkit root lattice of a widget model.

    Returns:
        BlenderLattice.
    Raises:
        NotRepresentable: child lattices, a rest shape that is not an affine grid, or an axis whose
            basis Blender has not (see _axis_candidates); the message says which.
    """
    name = model.name(lattice)
    if model.children(lattice):
        raise NotRepresentable("lattice '%s' has child lattices: Blender's lattice modifier has no nesting "
                               "(export each level by itself)" % name)
    counts = [int(c) for c in model.counts(lattice)]
    settings = model.latticeSettings(lattice)
    per_axis = [_axis_candidates(ffdkit, settings.basis[a], counts[a], "uvw"[a]) for a in range(3)]
    rest = np.asarray(model.restPoints(lattice), dtype=np.float64)
    control = np.asarray(model.controlPoints(lattice), dtype=np.float64)
    scale = max(1.0, float(np.abs(rest).max()))
    for choice in _products(per_axis):
        greville = _grid(*(b + h * form.greville for _, _, form, b, h in choice))  # knot 0 <-> b
        # The rest shape must be an affine image of the knots' Greville grid (then rest = identity).
        design = np.column_stack([greville, np.ones(len(greville))])
        affine, *_ = np.linalg.lstsq(design, rest, rcond=None)
        if np.abs(design @ affine - rest).max() > 1e-9 * scale:
            raise NotRepresentable("lattice '%s': its rest shape is not a box grid (a user-shaped lattice): "
                                   "Blender's lattice rest is a uniform grid" % name)
        linear = affine[:3].T
        moves = np.linalg.solve(linear, (control - rest).T).T  # in the Greville grid's units
        h = np.array([c[4] for c in choice])
        index_moves = moves / h
        pinvs = [np.linalg.pinv(form.matrix) for _, _, form, _, _ in choice]
        blender_counts = [c[1] for c in choice]
        delta = _apply_axes(pinvs, index_moves, counts)
        rebuilt = _apply_axes([form.matrix for _, _, form, _, _ in choice], delta, blender_counts)
        if np.abs(rebuilt - index_moves).max() > 1e-9 * max(1.0, np.abs(index_moves).max()):
            continue
        origin, spacing = blender_grid(blender_counts)
        points = _grid(*(origin[a] + spacing[a] * np.arange(blender_counts[a]) for a in range(3))) + spacing * delta
        # lattice space x -> parameter b + h (x - origin) / spacing -> local (affine) -> world (frame)
        to_parameter = np.eye(4)
        to_parameter[:3, :3] = np.diag(h / spacing)
        to_parameter[:3, 3] = np.array([c[3] for c in choice]) - h * origin / spacing
        to_local = np.eye(4)
        to_local[:3, :3] = linear
        to_local[:3, 3] = affine[3]
        matrix = np.asarray(model.latticeFrame(lattice), dtype=np.float64) @ to_local @ to_parameter
        gram = matrix[:3, :3].T @ matrix[:3, :3]
        if np.abs(gram - np.diag(np.diag(gram))).max() > 1e-6 * np.abs(gram).max():  # float32 rotations
            raise NotRepresentable("lattice '%s': its placement shears the lattice: a Blender object's "
                                   "matrix holds location, rotation and scale only" % name)
        warnings = []
        if settings.outside != ffdkit.ffd.OutsidePolicy.clampEdge():
            warnings.append("lattice '%s' leaves points outside it %s; Blender's lattice moves them with its "
                            "border: the two agree inside the lattice only" % (name, _outside_words(settings.outside)))
        return BlenderLattice(blender_counts, [c[0] for c in choice], points, matrix, warnings)
    raise NotRepresentable("lattice '%s': its control points are not a move of Blender's cardinal, Catmull-Rom "
                           "or B-spline points (the cubic double-knot form holds more shapes than those)" % name)


def _outside_words(policy):
    kind = str(policy.kind).split(".")[-1]
    return {"Identity": "where they are", "Extrapolate": "to the end polynomials",
            "Falloff": "blending out over a distance"}.get(kind, kind)


def _products(per_axis):
    for a in per_axis[0]:
        for b in per_axis[1]:
            for c in per_axis[2]:
                yield (a, b, c)

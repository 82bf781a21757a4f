"""Control-point weights (rational lattices, Lamousin & Waggenspack 1994) from Python: the
quarter circle against its closed form, the ratio formula against numpy, the widget model's
weight edits and their widget-file round trip."""

import math

import numpy as np
import pytest

import ffdkit
from ffdkit import ffd, scenes, widgets
from reference import bernstein


def quarter_circle_lattice():
    lattice = ffd.makeBoxLattice(counts=(3, 2, 2), bases=ffd.AxisBasis.bernstein())
    points = lattice.controlPoints.copy()
    weights = np.ones(lattice.pointCount)
    corners = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    for k in range(2):
        for j in range(2):
            for i in range(3):
                f = lattice.index(i, j, k)
                points[f] = [(1 + j) * corners[i][0], (1 + j) * corners[i][1], k]
                if i == 1:
                    weights[f] = 1 / math.sqrt(2)
    lattice.setControlPoints(points)
    lattice.weights = weights
    return lattice


def test_a_quarter_circle_weight_puts_a_segment_on_the_unit_circle():
    lattice = quarter_circle_lattice()
    assert lattice.isRational and not lattice.restIsRational
    u = np.linspace(0.0, 1.0, 201)
    x = lattice.evaluate(np.column_stack([u, np.zeros_like(u), np.full_like(u, 0.5)]))
    assert np.max(np.abs(np.hypot(x[:, 0], x[:, 1]) - 1.0)) <= 1e-15
    q = np.column_stack([u, np.zeros_like(u), np.full_like(u, 0.25)])
    out = ffd.deformPoints(lattice, q)
    assert np.max(np.abs(np.hypot(out[:, 0], out[:, 1]) - 1.0)) <= 1e-15


def test_evaluation_is_the_ratio_of_the_weighted_sums():
    rng = np.random.default_rng(36)
    counts = (4, 3, 5)
    lattice = ffd.makeBoxLattice(counts=counts, bases=ffd.AxisBasis.bernstein())
    lattice.setControlPoints(lattice.controlPoints + rng.uniform(-0.1, 0.1, (lattice.pointCount, 3)))
    w = rng.uniform(0.3, 3.0, lattice.pointCount)
    lattice.setWeights(w)
    np.testing.assert_array_equal(lattice.weights, w)
    uvw = rng.uniform(0.0, 1.0, (50, 3))
    P = lattice.controlPoints
    expected = []
    for t in uvw:
        num, den = np.zeros(3), 0.0
        for k in range(counts[2]):
            for j in range(counts[1]):
                for i in range(counts[0]):
                    b = bernstein(counts[0] - 1, t[0])[i] * bernstein(counts[1] - 1, t[1])[j] * \
                        bernstein(counts[2] - 1, t[2])[k] * w[lattice.index(i, j, k)]
                    num += b * P[lattice.index(i, j, k)]
                    den += b
        expected.append(num / den)
    np.testing.assert_allclose(lattice.evaluate(uvw), np.array(expected), rtol=0, atol=1e-14)


def test_bad_weights_raise_lattice_errors_naming_the_point():
    lattice = ffd.makeBoxLattice(counts=(2, 2, 2), bases=ffd.AxisBasis.bernstein())
    w = np.ones(8)
    w[5] = -1.0
    with pytest.raises(ffdkit.LatticeError, match="weight 5 must be finite and > 0"):
        lattice.setWeights(w)
    with pytest.raises(ffdkit.LatticeError, match="expected 8 weights"):
        lattice.weights = np.ones(7)
    assert not lattice.isRational


def test_the_widget_model_weights_round_trip_through_a_widget_file():
    model = widgets.WidgetModel()
    box = model.addLattice("box", (3, 3, 3))
    assert not model.isRational(box)
    model.setWeight(box, 13, 2.5)
    assert model.isRational(box) and model.weights(box)[13] == 2.5
    assert model.ffdLattice(box).weight(13) == 2.5
    text = scenes.widgetFileText(model)
    assert '"version": 2' in text and '"weights"' in text
    with pytest.raises(ffdkit.WidgetError, match="must be finite and > 0"):
        model.setWeight(box, 0, 0.0)
    model.setWeights(box, np.ones(27))
    assert '"version": 1' in scenes.widgetFileText(model)

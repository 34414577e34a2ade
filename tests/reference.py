"""An independent statement of the equations of motion (Eq. 10, 31-32) for
scipy's ``solve_ivp``: storey drifts as coordinates (the paper's choice),
plain Python, nothing shared with the library's kernel but the case data."""

import math

import numpy as np
from scipy.integrate import solve_ivp


def jankowski(delta, delta_dot, beta, xi, reduced_mass):
    """Eq. 3-4 with the sqrt(delta) damping of Jankowski (2005)."""
    if delta <= 0:
        return 0.0
    force = beta * delta**1.5
    if delta_dot > 0:
        force += 2 * xi * math.sqrt(beta * math.sqrt(delta) * reduced_mass) * delta_dot
    return force


def solve_reference(case, record, time_step, rtol=1e-9):
    """Integrate the case (a row of buildings, any contacts) under ``record`` with DOP853.

    Returns the solution (impact onsets of contact c in ``t_events[c]``) and a function giving each
    contact's pounding force at given times from the dense output, shape (contacts, times).
    """
    buildings = []
    for building in case.buildings:
        storeys = building.storeys
        buildings.append([
            (s.mass, s.stiffness, c, s.bouc_wen.alpha, s.bouc_wen.A, s.bouc_wen.beta, s.bouc_wen.gamma, s.bouc_wen.n)
            for s, c in zip(storeys, building.storey_damping())
        ])
    sizes = [len(b) for b in buildings]
    offsets = [sum(sizes[:b]) for b in range(len(sizes))]
    n = sum(sizes)
    contacts = [(c, c.damping_ratio(), case.reduced_mass_of(c)) for c in case.contacts]
    last = record.size - 1

    def floor(y, building, level, velocity=False):
        # Floor displacement = sum of the drifts below it.
        start = offsets[building - 1] + (n if velocity else 0)
        return sum(y[start : start + level])

    def penetration(y, contact):
        (left, right), (level_left, level_right) = contact.between, contact.levels
        return (floor(y, left, level_left) - floor(y, right, level_right) - contact.gap,
                floor(y, left, level_left, True) - floor(y, right, level_right, True))

    def forces(y):
        return [jankowski(*penetration(y, c), c.stiffness, xi, m) for c, xi, m in contacts]

    def rhs(t, y):
        k = min(int(t / time_step), last - 1)
        a_g = record[k] + (record[k + 1] - record[k]) * (t / time_step - k)
        external = [[0.0] * size for size in sizes]  # contact forces on each floor
        for (contact, _, _), force in zip(contacts, forces(y)):
            (left, right), (level_left, level_right) = contact.between, contact.levels
            external[left - 1][level_left - 1] -= force
            external[right - 1][level_right - 1] += force
        dydt = np.empty(3 * n)
        dydt[:n] = y[n : 2 * n]
        for b, offset in enumerate(offsets):
            shears = []
            for i, (m, stiffness, c, alpha, A, beta, gamma, n_bw) in enumerate(buildings[b]):
                u, u_dot, z = y[offset + i], y[n + offset + i], y[2 * n + offset + i]
                shears.append(alpha * stiffness * u + (1 - alpha) * stiffness * z + c * u_dot)
                dydt[2 * n + offset + i] = A * u_dot - beta * abs(u_dot) * abs(z) ** (n_bw - 1) * z - gamma * u_dot * abs(z) ** n_bw
            shears.append(0.0)
            below = 0.0  # acceleration of the floor below, relative to the ground
            for i, (m, *_rest) in enumerate(buildings[b]):
                acceleration = (-shears[i] + shears[i + 1] + external[b][i]) / m - a_g
                dydt[n + offset + i] = acceleration - below
                below = acceleration
        return dydt

    def onset_event(contact):
        def onset(t, y):
            return penetration(y, contact)[0]
        onset.direction = 1
        return onset

    solution = solve_ivp(rhs, (0, last * time_step), np.zeros(3 * n), method="DOP853", rtol=rtol,
                         atol=rtol * 1e-3, max_step=time_step, dense_output=True,
                         events=[onset_event(c) for c, _, _ in contacts])

    def force_at(times):
        states = solution.sol(times)
        return np.array([forces(y) for y in states.T]).T

    return solution, force_at

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
    """Integrate the case under ``record`` with DOP853.

    Returns the solution (impact onsets in ``t_events[0]``) and a function
    giving the pounding force at given times from the dense output.
    """
    buildings = []
    for building in case.buildings:
        storeys = building.storeys
        buildings.append([
            (s.mass, s.stiffness, c, s.bouc_wen.alpha, s.bouc_wen.A, s.bouc_wen.beta, s.bouc_wen.gamma, s.bouc_wen.n)
            for s, c in zip(storeys, building.storey_damping())
        ])
    sizes = [len(b) for b in buildings]
    n = sum(sizes)
    contact = case.contact
    xi = contact.damping_ratio()
    m_reduced = case.reduced_mass
    level_1, level_2 = contact.levels
    last = record.size - 1

    def penetration(y):
        # Floor displacement = sum of the drifts below it.
        d1 = sum(y[:level_1])
        v1 = sum(y[n : n + level_1])
        d2 = sum(y[sizes[0] : sizes[0] + level_2])
        v2 = sum(y[n + sizes[0] : n + sizes[0] + level_2])
        return d1 - d2 - contact.gap, v1 - v2

    def rhs(t, y):
        k = min(int(t / time_step), last - 1)
        a_g = record[k] + (record[k + 1] - record[k]) * (t / time_step - k)
        delta, delta_dot = penetration(y)
        force = jankowski(delta, delta_dot, contact.stiffness, xi, m_reduced)
        dydt = np.empty(3 * n)
        dydt[:n] = y[n : 2 * n]
        for b, offset in ((0, 0), (1, sizes[0])):
            shears = []
            for i, (m, stiffness, c, alpha, A, beta, gamma, n_bw) in enumerate(buildings[b]):
                u, u_dot, z = y[offset + i], y[n + offset + i], y[2 * n + offset + i]
                shears.append(alpha * stiffness * u + (1 - alpha) * stiffness * z + c * u_dot)
                dydt[2 * n + offset + i] = A * u_dot - beta * abs(u_dot) * abs(z) ** (n_bw - 1) * z - gamma * u_dot * abs(z) ** n_bw
            shears.append(0.0)
            below = 0.0  # acceleration of the floor below, relative to the ground
            for i, (m, *_rest) in enumerate(buildings[b]):
                floor_force = -shears[i] + shears[i + 1]
                if b == 0 and i == level_1 - 1:
                    floor_force -= force
                if b == 1 and i == level_2 - 1:
                    floor_force += force
                acceleration = floor_force / m - a_g
                dydt[n + offset + i] = acceleration - below
                below = acceleration
        return dydt

    def onset(t, y):
        return penetration(y)[0]

    onset.direction = 1
    solution = solve_ivp(rhs, (0, last * time_step), np.zeros(3 * n), method="DOP853", rtol=rtol,
                         atol=rtol * 1e-3, max_step=time_step, dense_output=True, events=onset)

    def force_at(times):
        states = solution.sol(times)
        return np.array([jankowski(*penetration(y), contact.stiffness, xi, m_reduced) for y in states.T])

    return solution, force_at

"""The compiled mechanics: the contact laws (Eq. 3-5), the Bouc-Wen law
(Eq. 2), and every compiled function that calls them: the time-history
kernel of a row of shear buildings with Bouc-Wen storeys and impact elements
between neighbouring floors under one ground-acceleration record (Eq. 10,
31-32, 38-39), one impact of two free masses, and a storey's hysteresis
along a drift path.

Numba's on-disk cache of a compiled function does not notice an edit to a
compiled function it calls in another file, so every compiled call tree of
the laws lives here, in one file.

Numba-compiled (cached on disk, and releasing the GIL so that threads run
records in parallel). The equations are integrated with the Dormand-Prince
5(4) pair under error control: outside contact the step is capped by the
record's sampling interval; the stiff impacts shrink it as they need. Steps
never straddle a record sample, so the piecewise-linear ground acceleration
is smooth within each step, and the onset of every impact is located (the
step is cut to end on it), so that the impact velocity is measured and the
force law's kink at delta = 0 never falls inside a step.

The state is y = (d, v, z): floor displacements relative to the ground,
their velocities and the storeys' hysteretic displacements, for all floors
of building 1, then building 2, and so on. Contact c joins floor
``contact_floors[c, 0]`` (left) to floor ``contact_floors[c, 1]`` (right);
its penetration is d_left - d_right - gap.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# Codes of the contact laws (the index of the law in ``contact.CONTACT_LAWS``).
JANKOWSKI, HERTZ, HERTZDAMP, LINEAR = range(4)

# Columns of the per-floor parameter table.
MASS, STIFFNESS, DAMPING, ALPHA, BW_A, BW_BETA, BW_GAMMA, BW_N = range(8)
# Columns of the per-contact parameter table.
C_MODEL, C_GAP, C_STIFFNESS, C_DAMPING_RATIO, C_REDUCED_MASS = range(5)
# The per-record summary: the record's columns, then a block of CONTACT_COLUMNS per contact.
S_STATUS, S_TIME, S_STEPS = range(3)
RECORD_COLUMNS = 3
(
    S_FORCE_MAX,
    S_IMPACTS,
    S_PENETRATION_MAX,
    S_IMPACT_VELOCITY_MAX,
    S_DISPLACEMENT_MAX_1,
    S_DISPLACEMENT_MAX_2,
    S_RELATIVE_MAX,
) = range(7)
CONTACT_COLUMNS = 7
# Status codes.
OK, NOT_FINITE, RUNAWAY, STEP_UNDERFLOW, HISTORY_FULL, STEP_LIMIT = range(6)
TRIALS_PER_SAMPLE = 1000  # step trials allowed per record sample (and a million more): beyond, too stiff to integrate

# Dormand-Prince 5(4) tableau.
_C2, _C3, _C4, _C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
_A21 = 1 / 5
_A31, _A32 = 3 / 40, 9 / 40
_A41, _A42, _A43 = 44 / 45, -56 / 15, 32 / 9
_A51, _A52, _A53, _A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
_A61, _A62, _A63, _A64, _A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
_B1, _B3, _B4, _B5, _B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
_E1, _E3, _E4, _E5, _E6, _E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40  # 5th - 4th order


# --- the laws -----------------------------------------------------------------


@njit(cache=True, nogil=True)
def contact_force(model, delta, delta_dot, stiffness, damping_ratio, reduced_mass, approach_velocity):
    """Pounding force [N] for penetration ``delta`` [m] and its rate [m/s], Eq. 3.

    Parameters
    ----------
    model : int
        Code of the law (:data:`JANKOWSKI`, ...).
    delta, delta_dot : float
        Penetration and penetration rate.
    stiffness : float
        beta [N/m^1.5] (``linear``: k [N/m]).
    damping_ratio : float
        ``Contact.damping_ratio()`` (``hertzdamp``: 3 (1 - e^2) / 4).
    reduced_mass : float
        m1 m2 / (m1 + m2) of the colliding floors [kg].
    approach_velocity : float
        Penetration rate at the onset of this impact [m/s] (``hertzdamp`` only).
    """
    if delta <= 0.0:
        return 0.0
    if model == LINEAR:
        damping = 2.0 * damping_ratio * math.sqrt(stiffness * reduced_mass)
        return max(stiffness * delta + damping * delta_dot, 0.0)
    elastic = stiffness * delta * math.sqrt(delta)
    if model == JANKOWSKI:
        if delta_dot > 0.0:
            damping = 2.0 * damping_ratio * math.sqrt(stiffness * math.sqrt(delta) * reduced_mass)
            return elastic + damping * delta_dot
        return elastic
    if model == HERTZDAMP:
        # damping_ratio holds 3 (1 - e^2) / 4; the law divides by the approach velocity.
        return max(elastic * (1.0 + damping_ratio * delta_dot / max(approach_velocity, 1e-12)), 0.0)
    return elastic


@njit(cache=True, nogil=True)
def bouc_wen_rate(velocity, z, A, beta, gamma, n):
    """dz/dt of the Bouc-Wen model, Eq. 2 [m/s].

    Parameters
    ----------
    velocity : float
        Storey drift velocity [m/s].
    z : float
        Hysteretic displacement [m].
    A, beta, gamma, n : float
        Bouc-Wen parameters, ``beta`` and ``gamma`` in [1/m^n].
    """
    abs_z = abs(z)
    # The common exponents without pow(): it dominates the kernel's cost otherwise.
    if n == 1.0:
        abs_z_n = abs_z
    elif n == 2.0:
        abs_z_n = abs_z * abs_z
    else:
        abs_z_n = abs_z**n
    # |z|^(n-1) z = |z|^n sign(z)
    signed = abs_z_n if z >= 0.0 else -abs_z_n
    return A * velocity - beta * abs(velocity) * signed - gamma * velocity * abs_z_n


# --- two buildings under one record -----------------------------------------


@njit(cache=True, nogil=True)
def derivatives(ground_acceleration, y, dydt, floors, below, contacts, contact_floors, approach_velocity, forces):
    """Write dy/dt into ``dydt`` and each contact's pounding force [N] into ``forces``.

    Equations of motion of the shear buildings relative to the ground,
    M d'' + sum of storey forces + contacts = -M 1 a_g (Eq. 10, 38), and Eq. 2
    for every storey.
    """
    n = below.size
    for i in range(n):
        dydt[i] = y[n + i]
        dydt[n + i] = 0.0
    for i in range(n):
        j = below[i]
        drift = y[i]
        drift_rate = y[n + i]
        if j >= 0:
            drift -= y[j]
            drift_rate -= y[n + j]
        z = y[2 * n + i]
        k = floors[i, STIFFNESS]
        alpha = floors[i, ALPHA]
        # Eq. 36 plus the storey's viscous damper.
        storey_force = alpha * k * drift + (1.0 - alpha) * k * z + floors[i, DAMPING] * drift_rate
        dydt[2 * n + i] = bouc_wen_rate(drift_rate, z, floors[i, BW_A], floors[i, BW_BETA], floors[i, BW_GAMMA], floors[i, BW_N])
        dydt[n + i] -= storey_force
        if j >= 0:
            dydt[n + j] += storey_force
    for c in range(contacts.shape[0]):
        left, right = contact_floors[c, 0], contact_floors[c, 1]
        force = contact_force(int(contacts[c, C_MODEL]), y[left] - y[right] - contacts[c, C_GAP], y[n + left] - y[n + right],
                              contacts[c, C_STIFFNESS], contacts[c, C_DAMPING_RATIO], contacts[c, C_REDUCED_MASS],
                              approach_velocity[c])
        forces[c] = force
        dydt[n + left] -= force
        dydt[n + right] += force
    for i in range(n):
        dydt[n + i] = dydt[n + i] / floors[i, MASS] - ground_acceleration


@njit(cache=True, nogil=True)
def _crossing(p0, p1, m0, m1):
    """Root s in [0, 1] of the cubic Hermite interpolant with values p0 <= 0 < p1
    and end slopes m0, m1 (per unit s); and its slope there."""
    lo, hi = 0.0, 1.0
    for _ in range(50):
        s = 0.5 * (lo + hi)
        s2 = s * s
        s3 = s2 * s
        value = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1
        if value > 0.0:
            hi = s
        else:
            lo = s
    s = hi
    s2 = s * s
    slope = (6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p1 + (3 * s2 - 2 * s) * m1
    return s, slope


@njit(cache=True, nogil=True)
def _peak_between(t0, f0, t1, f1, t2, f2):
    """Peak of the parabola through three samples around a local maximum f1
    (t0 < t1 < t2): a peak of force or penetration rarely falls on a step end."""
    d0 = (f1 - f0) / (t1 - t0)
    d1 = (f2 - f1) / (t2 - t1)
    curvature = (d1 - d0) / (t2 - t0)
    if curvature >= 0.0:
        return f1
    t_peak = 0.5 * (t0 + t1) - d0 / (2.0 * curvature)
    if t_peak <= t0 or t_peak >= t2:
        return f1
    return max(f1, f1 + d0 * (t_peak - t1) + curvature * (t_peak - t0) * (t_peak - t1))


@njit(cache=True, nogil=True)
def integrate_record(record, time_step, y0, floors, below, contacts, contact_floors, rtol, atol, displacement_limit, summary,
                     history_time, history_state, history_force):
    """Integrate one record; fill ``summary`` (the S_* columns: the record's, then a block per contact).

    Parameters
    ----------
    record : ndarray
        Ground acceleration at t = k * time_step [m/s^2].
    y0 : ndarray
        Initial state (d, v, z).
    contacts, contact_floors : ndarray
        The contacts' parameters (C_* columns) and their (left, right) floors, one row each.
    rtol, atol : float, ndarray
        Relative and per-component absolute tolerances of the local error.
    displacement_limit : float
        A floor displacement beyond this [m] is a runaway response.
    history_time, history_state, history_force : ndarray
        Filled at every accepted step when ``history_time.size > 0`` (the force: one column per contact).

    Returns
    -------
    int
        Number of history rows written.
    """
    n_state = y0.size
    n = below.size
    n_contacts = contacts.shape[0]
    store = history_time.size > 0
    y = y0.copy()
    y_new = np.empty(n_state)
    y_stage = np.empty(n_state)
    k1, k2, k3, k4 = np.empty(n_state), np.empty(n_state), np.empty(n_state), np.empty(n_state)
    k5, k6, k7 = np.empty(n_state), np.empty(n_state), np.empty(n_state)
    forces, stage_forces, approach_velocity = np.zeros(n_contacts), np.zeros(n_contacts), np.zeros(n_contacts)
    rates, delta_new = np.zeros(n_contacts), np.zeros(n_contacts)
    summary[:] = 0.0
    peaks = np.zeros((n_contacts, CONTACT_COLUMNS))  # contiguous here, copied into ``summary`` at the end
    left, right = contact_floors[:, 0].copy(), contact_floors[:, 1].copy()
    onset = np.zeros(n_contacts, dtype=np.bool_)
    for c in range(n_contacts):
        peaks[c, S_DISPLACEMENT_MAX_1] = abs(y[left[c]])
        peaks[c, S_DISPLACEMENT_MAX_2] = abs(y[right[c]])
        # Over the accepted steps, as the onset of an impact is detected: with the gap out of reach this is the
        # free motion's peak, and a record pounds at gap d exactly when that peak exceeds d.
        peaks[c, S_RELATIVE_MAX] = y[left[c]] - y[right[c]]
    steps = 0
    stored = 0
    h_min = 1e-12 * max(time_step, 1.0)
    trials_left = TRIALS_PER_SAMPLE * record.size + 1_000_000
    derivatives(record[0], y, k1, floors, below, contacts, contact_floors, approach_velocity, forces)
    # The last two accepted times, and each contact's force and penetration there, for the peak between steps.
    t_back_2, t_back_1 = -2.0, -1.0
    force_back_2, force_back_1 = np.zeros(n_contacts), forces.copy()
    delta_back_2, delta_back_1 = np.full(n_contacts, -1.0), np.full(n_contacts, -1.0)
    if store:
        history_time[0] = 0.0
        history_state[0, :] = y
        history_force[0, :] = forces
        stored = 1
    h = 0.1 * time_step
    t = 0.0
    status = OK
    for sample in range(record.size - 1):
        t_start = sample * time_step
        t_end = t_start + time_step
        a0 = record[sample]
        slope = (record[sample + 1] - a0) / time_step
        t = t_start
        while t < t_end and status == OK:
            last = False
            h_try = h
            if t + h_try >= t_end - 1e-12 * time_step:
                h_try = t_end - t
                last = True
            for c in range(n_contacts):
                if y[left[c]] - y[right[c]] <= contacts[c, C_GAP]:
                    # Out of contact, the law's memory follows the closing velocity, so that
                    # the step into the next impact starts with the right one (hertzdamp).
                    approach_velocity[c] = max(y[n + left[c]] - y[n + right[c]], 0.0)
            # Dormand-Prince stages; the ground acceleration is linear in t here.
            for i in range(n_state):
                y_stage[i] = y[i] + h_try * _A21 * k1[i]
            derivatives(a0 + slope * (t + _C2 * h_try - t_start), y_stage, k2, floors, below, contacts, contact_floors,
                        approach_velocity, stage_forces)
            for i in range(n_state):
                y_stage[i] = y[i] + h_try * (_A31 * k1[i] + _A32 * k2[i])
            derivatives(a0 + slope * (t + _C3 * h_try - t_start), y_stage, k3, floors, below, contacts, contact_floors,
                        approach_velocity, stage_forces)
            for i in range(n_state):
                y_stage[i] = y[i] + h_try * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
            derivatives(a0 + slope * (t + _C4 * h_try - t_start), y_stage, k4, floors, below, contacts, contact_floors,
                        approach_velocity, stage_forces)
            for i in range(n_state):
                y_stage[i] = y[i] + h_try * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
            derivatives(a0 + slope * (t + _C5 * h_try - t_start), y_stage, k5, floors, below, contacts, contact_floors,
                        approach_velocity, stage_forces)
            for i in range(n_state):
                y_stage[i] = y[i] + h_try * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i])
            derivatives(a0 + slope * (t + h_try - t_start), y_stage, k6, floors, below, contacts, contact_floors,
                        approach_velocity, stage_forces)
            for i in range(n_state):
                y_new[i] = y[i] + h_try * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i])
            derivatives(a0 + slope * (t + h_try - t_start), y_new, k7, floors, below, contacts, contact_floors,
                        approach_velocity, forces)
            error = 0.0
            for i in range(n_state):
                local = h_try * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
                scale = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
                error += (local / scale) ** 2
            error = math.sqrt(error / n_state)
            if not math.isfinite(error):
                status = NOT_FINITE
                break
            trials_left -= 1
            if trials_left < 0:
                status = STEP_LIMIT
                break
            if error > 1.0:
                h = h_try * max(0.2, 0.9 * error**-0.2)
                if h < h_min:
                    status = STEP_UNDERFLOW
                continue
            # Locate the onset of an impact: end the step on the first one inside it.
            cut = 1.0
            any_onset = False
            for c in range(n_contacts):
                delta_0 = y[left[c]] - y[right[c]] - contacts[c, C_GAP]
                delta_new[c] = y_new[left[c]] - y_new[right[c]] - contacts[c, C_GAP]
                onset[c] = delta_0 <= 0.0 and delta_new[c] > 0.0
                if onset[c]:
                    any_onset = True
                    s, rates[c] = _crossing(delta_0, delta_new[c], h_try * (y[n + left[c]] - y[n + right[c]]),
                                            h_try * (y_new[n + left[c]] - y_new[n + right[c]]))
                    if 0.01 < s < 0.99 and s * h_try > h_min:
                        cut = min(cut, s)
            if cut < 1.0:
                h = cut * h_try
                continue
            for c in range(n_contacts):
                if onset[c]:
                    peaks[c, S_IMPACTS] += 1
                    approach_velocity[c] = rates[c] / h_try
                    peaks[c, S_IMPACT_VELOCITY_MAX] = max(peaks[c, S_IMPACT_VELOCITY_MAX], approach_velocity[c])
            # Accept the step.
            t = t_end if last else t + h_try
            steps += 1
            for i in range(n_state):
                y[i] = y_new[i]
            if any_onset:
                # The law's memory (hertzdamp) changed: re-evaluate the slope.
                derivatives(a0 + slope * (t - t_start), y, k1, floors, below, contacts, contact_floors, approach_velocity, forces)
            else:
                for i in range(n_state):
                    k1[i] = k7[i]
            for c in range(n_contacts):
                force, f1, f2 = forces[c], force_back_1[c], force_back_2[c]
                peaks[c, S_FORCE_MAX] = max(peaks[c, S_FORCE_MAX], abs(force))
                if f1 > 0.0 and f1 >= f2 and f1 >= force and f2 > 0.0:
                    peaks[c, S_FORCE_MAX] = max(peaks[c, S_FORCE_MAX], _peak_between(t_back_2, f2, t_back_1, f1, t, force))
                delta, d1, d2 = delta_new[c], delta_back_1[c], delta_back_2[c]
                peaks[c, S_PENETRATION_MAX] = max(peaks[c, S_PENETRATION_MAX], delta)
                if d1 > 0.0 and d2 > 0.0 and d1 >= d2 and d1 >= delta:
                    peaks[c, S_PENETRATION_MAX] = max(peaks[c, S_PENETRATION_MAX], _peak_between(t_back_2, d2, t_back_1, d1, t, delta))
                force_back_2[c], force_back_1[c] = f1, force
                delta_back_2[c], delta_back_1[c] = d1, delta
                peaks[c, S_DISPLACEMENT_MAX_1] = max(peaks[c, S_DISPLACEMENT_MAX_1], abs(y[left[c]]))
                peaks[c, S_DISPLACEMENT_MAX_2] = max(peaks[c, S_DISPLACEMENT_MAX_2], abs(y[right[c]]))
                peaks[c, S_RELATIVE_MAX] = max(peaks[c, S_RELATIVE_MAX], y[left[c]] - y[right[c]])
            t_back_2, t_back_1 = t_back_1, t
            for i in range(n):
                if not abs(y[i]) <= displacement_limit:
                    status = RUNAWAY if math.isfinite(y[i]) else NOT_FINITE
            if store and status == OK:
                if stored == history_time.size:
                    status = HISTORY_FULL
                else:
                    history_time[stored] = t
                    history_state[stored, :] = y
                    history_force[stored, :] = forces
                    stored += 1
            if not last:
                h = h_try * min(5.0, max(0.2, 0.9 * max(error, 1e-10) ** -0.2))
        if status != OK:
            break
    summary[S_STATUS] = status
    summary[S_TIME] = t
    summary[S_STEPS] = steps
    summary[RECORD_COLUMNS:] = peaks.ravel()
    return stored


@njit(cache=True, nogil=True)
def integrate_batch(records, time_step, y0, floors, below, contacts, contact_floors, rtol, atol, displacement_limit, summaries):
    """``integrate_record`` for every row of ``records``, no histories kept.
    Stops at the first failed record (its status says why)."""
    no_time = np.empty(0)
    no_state = np.empty((0, y0.size))
    no_force = np.empty((0, contacts.shape[0]))
    for r in range(records.shape[0]):
        integrate_record(records[r], time_step, y0, floors, below, contacts, contact_floors, rtol, atol,
                         displacement_limit, summaries[r], no_time, no_state, no_force)
        if summaries[r, S_STATUS] != OK:
            break


# --- one impact of two free masses -------------------------------------------


@njit(cache=True)
def _impact_rates(model, damping_ratio, opposing_force, x, rate):
    """x'' = -(F_c(x, x') + f0) for unit reduced mass and unit stiffness."""
    return -(contact_force(model, x, rate, 1.0, damping_ratio, 1.0, 1.0) + opposing_force)


@njit(cache=True)
def single_impact_peak(model, damping_ratio, opposing_force, steps):
    """Peak contact force of two masses of reduced mass 1 meeting at unit
    speed under unit stiffness (beta = 1, or k = 1 for ``linear``), against a
    constant force f0 = ``opposing_force`` opposing the approach:
    x'' = -(F_c(x, x') + f0), x(0) = 0, x'(0) = 1, to the largest penetration
    (the force only falls after it), and one step beyond.

    Classical RK4 with ``steps`` steps per time scale 1 / (1 + f0); the first
    tenth of it on a mesh graded as (k / m)^4, where the damped laws' force
    grows as t^(1/4) from the touch; the peak is taken through the parabola
    of the three samples around the largest (:func:`_peak_between`). 4000
    steps give the peak to about 1e-8 (tests/test_contact.py)."""
    time_scale = 1.0 / (1.0 + opposing_force)
    graded = max(steps // 10, 4)
    start = 0.1 * time_scale
    h_uniform = time_scale / steps
    t, x, rate = 0.0, 0.0, 1.0
    t_back_2, f_back_2, t_back_1, f_back_1 = -2.0, -1.0, -1.0, -1.0
    peak = 0.0
    turned = False
    for k in range(100 * steps + graded):
        if k < graded:
            h = start * (((k + 1) / graded) ** 4 - (k / graded) ** 4)
        else:
            h = h_uniform
        k1x, k1v = rate, _impact_rates(model, damping_ratio, opposing_force, x, rate)
        k2x = rate + 0.5 * h * k1v
        k2v = _impact_rates(model, damping_ratio, opposing_force, x + 0.5 * h * k1x, k2x)
        k3x = rate + 0.5 * h * k2v
        k3v = _impact_rates(model, damping_ratio, opposing_force, x + 0.5 * h * k2x, k3x)
        k4x = rate + h * k3v
        k4v = _impact_rates(model, damping_ratio, opposing_force, x + h * k3x, k4x)
        x += h * (k1x + 2.0 * k2x + 2.0 * k3x + k4x) / 6.0
        rate += h * (k1v + 2.0 * k2v + 2.0 * k3v + k4v) / 6.0
        t += h
        force = contact_force(model, x, rate, 1.0, damping_ratio, 1.0, 1.0)
        peak = max(peak, force)
        if f_back_1 > 0.0 and f_back_2 > 0.0 and f_back_1 >= f_back_2 and f_back_1 >= force:
            peak = max(peak, _peak_between(t_back_2, f_back_2, t_back_1, f_back_1, t, force))
        t_back_2, f_back_2, t_back_1, f_back_1 = t_back_1, f_back_1, t, force
        if rate <= 0.0:
            if turned:  # one sample past the turn, for the parabola around a peak at it (Hertz)
                break
            turned = True
    return peak


# --- a storey along a drift path ---------------------------------------------


@njit(cache=True)
def hysteretic_path(drift, A, beta, gamma, n):
    """z along a prescribed drift history from rest (Eq. 2 divided by the
    positive time step: dz/du), by the trapezoidal predictor-corrector on each
    increment [m]."""
    z = np.zeros(drift.size)
    for i in range(1, drift.size):
        du = drift[i] - drift[i - 1]
        slope_0 = bouc_wen_rate(du, z[i - 1], A, beta, gamma, n)
        z_predicted = z[i - 1] + slope_0
        slope_1 = bouc_wen_rate(du, z_predicted, A, beta, gamma, n)
        z[i] = z[i - 1] + 0.5 * (slope_0 + slope_1)
    return z


@njit(cache=True)
def bouc_wen_rates(velocity, z, A, beta, gamma, n):
    """Eq. 2 (:func:`bouc_wen_rate`) at every sample [m/s]."""
    out = np.empty(velocity.size)
    for i in range(velocity.size):
        out[i] = bouc_wen_rate(velocity[i], z[i], A, beta, gamma, n)
    return out

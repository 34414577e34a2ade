"""The running part of an exported OpenSeesPy model (``pounding export opensees``).

The two parts below the marker lines are copied, as they are, into every
``model.py`` that :mod:`pounding.export.opensees` writes: the imports at its
top, the model's code after the case's data (``CASE_NAME``, ``BUILDINGS``,
``CONTACTS``, ``TIME_STEP``, ``RECORDS``, which the code reads). It imports nothing
from ``pounding`` and only the standard library and ``openseespy``, so that
the model runs where pounding is not installed. Importing this module does
not import ``openseespy``: the exporter reads :data:`CONTACT_MATERIALS` from it.
"""

# --- model.py: imports ---------------------------------------------------------------------------------------------
import argparse
import ctypes
import importlib.util
import json
import math
import os
import sys
import time

# --- model.py: the OpenSeesPy model --------------------------------------------------------------------------------
# Units: SI throughout (m, kg, s, N). Node tags: 1000 b + f is floor f of building b (f = 0: its ground), and
# so is the tag of the storey element below that floor; contact c (from 1, the case's order) is element and
# material CONTACT_TAGS + c.

CONTACT_MATERIALS = {"jankowski": "JankowskiImpact", "hertzdamp": "Hertzdamp", "hertz": "Hertzdamp"}
"""The OpenSees uniaxialMaterial standing for each of pounding's contact laws."""
GAP_AT_TOUCH = 1e-12
"""[m] The impact materials refuse a gap >= 0 (they stop the process): a gap of 0 is written as -1e-12 m."""
BOUC_WEN_TOLERANCE = 1e-12
"""[m] Tolerance of the BoucWen material's Newton iteration on z (OpenSees' default, 1e-8 m, is 1e-6 of a 1 cm yield drift)."""
NEWTON_TOLERANCE = 1e-10
"""[m] The equilibrium iterations of a step stop when the displacement increment is below this (NormDispIncr)."""
NEWTON_ITERATIONS = 50
"""Iterations Newton is given on a step."""
FALLBACK_ALGORITHMS = (("NewtonLineSearch", "-type", "Bisection"), ("KrylovNewton",), ("ModifiedNewton", "-initial"))
"""Tried in turn, as OpenSees users do, on a step where Newton fails; then the step is cut in halves."""
FALLBACK_ITERATIONS = 200
"""Iterations each fallback algorithm is given."""
MOST_STEP_CUTS = 8
"""A step still failing after this many halvings (1/256 of it) fails the record."""
CONTACT_TAGS = 10000
"""Contact c's element and material are tagged CONTACT_TAGS + c: above every floor's and storey's tag (at most 8 buildings)."""


def import_opensees():
    """``openseespy.opensees``. On Python 3.11, pip installs openseespy 3.7.1.2, whose bundled
    liblapack.so.3 cannot find the libblas.so.3 beside it: load that one first (openseespy 3.8 on
    Python >= 3.12 imports cleanly, and there is nothing to load)."""
    spec = importlib.util.find_spec("openseespylinux")  # finds the package without running it
    if spec is not None and spec.submodule_search_locations:
        blas = os.path.join(list(spec.submodule_search_locations)[0], "lib", "libblas.so.3")
        if os.path.exists(blas):
            ctypes.CDLL(blas, mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


def floor_node(building, floor):
    """Tag of floor ``floor`` (0: the ground) of building ``building`` (from 1, left to right)."""
    return 1000 * building + floor


def build_model(ops):
    """Every building and an impact element for every contact, from BUILDINGS and CONTACTS."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    material = 100
    for building, storeys in enumerate(BUILDINGS, start=1):
        ops.node(floor_node(building, 0), 0.0)
        ops.fix(floor_node(building, 0), 1)
        for floor, storey in enumerate(storeys, start=1):
            # The floor's mass: the inertia term M x'' of Eq. 10 / 38, x relative to the ground.
            ops.node(floor_node(building, floor), 0.0, "-mass", storey["mass"])
            # Storey restoring force, Eq. 36: q = alpha k u + (1 - alpha) k z on the drift u, with z from
            # Eq. 2: z' = A u' - beta |u'| |z|^(n-1) z - gamma u' |z|^n. OpenSees' BoucWen takes GAMMA BEFORE
            # BETA: alpha, ko, n, gamma, beta, Ao, deltaA, deltaNu, deltaEta (all nine needed; the three
            # degradation rates are 0 here), then the tolerance of its Newton iteration on z.
            ops.uniaxialMaterial("BoucWen", material, storey["alpha"], storey["stiffness"], storey["n"],
                                 storey["gamma"], storey["beta"], storey["A"], 0.0, 0.0, 0.0, BOUC_WEN_TOLERANCE)
            # The storey's dashpot c u' (pounding's storey damping: 2 xi sqrt(k m) for one storey,
            # 2 xi k_i / omega_1 per storey for more, i.e. C = (2 xi / omega_1) K): a Viscous material.
            ops.uniaxialMaterial("Viscous", material + 1, storey["damping"], 1.0)
            # One zeroLength element per storey, from the floor below to this floor: its strain is the drift.
            ops.element("zeroLength", floor_node(building, floor), floor_node(building, floor - 1),
                        floor_node(building, floor), "-mat", material, material + 1, "-dir", 1, 1)
            material += 2
    for number, contact in enumerate(CONTACTS, start=1):
        # Each contact is its own impact element between the two floors that meet (Eq. 10), with its own
        # material (gap, law, stiffness, reduced mass): node i is the left building's floor, node j the right
        # one's, so the element's strain u_j - u_i = x_right - x_left = -(delta + gap), negative in contact.
        # All of them act in the one analysis: an impact at one floor moves the others.
        contact_material(ops, CONTACT_TAGS + number, contact)
        ops.element("zeroLength", CONTACT_TAGS + number, *contact_nodes(contact), "-mat", CONTACT_TAGS + number, "-dir", 1)


def contact_nodes(contact):
    """The tags of the contact's left and right floors."""
    (left, right), (level_left, level_right) = contact["between"], contact["levels"]
    return floor_node(left, level_left), floor_node(right, level_right)


def contact_material(ops, tag, contact):
    """The contact's impact material: compression-only, contact when the strain u_j - u_i falls below its
    gap, which must be negative (a gap >= 0 makes these materials stop the process)."""
    gap = -max(contact["gap"], GAP_AT_TOUCH)
    law = contact["law"]
    if law == "jankowski":
        # Eq. 3-5: F = beta delta^1.5 + c delta' while approaching (delta' > 0), beta delta^1.5 while
        # restoring, c = 2 xi sqrt(beta sqrt(delta) m1 m2 / (m1 + m2)), xi from the restitution (Eq. 5),
        # m1 and m2 the masses of this contact's two floors. JankowskiImpact: Kh, xi, mEff, gap, n.
        ops.uniaxialMaterial("JankowskiImpact", tag, contact["stiffness"], contact["damping"],
                             contact["reduced_mass"], gap, 1.5)
    elif law in ("hertzdamp", "hertz"):
        # Muthukumar & DesRoches (2006): F = beta delta^1.5 (1 + 3 (1 - e^2) / 4 delta' / v0), v0 the
        # approach velocity as the impact begins (OpenSees takes it at the end of the impact's first step);
        # Hertz, elastic, is the same with 0 for 3 (1 - e^2) / 4. Hertzdamp: Kh, xiNorm, gap, n.
        ops.uniaxialMaterial("Hertzdamp", tag, contact["stiffness"], contact["damping"], gap, 1.5)
    else:
        raise SystemExit(f"model.py: OpenSees has no material for the contact law {law!r}")


def set_up_analysis(ops, record):
    """The record as a Path time series (linear between samples, as pounding takes it), applied to
    every floor as the ground acceleration (UniformExcitation: the response is relative to the ground,
    the right-hand side -M 1 a_g of Eq. 10); Newmark's average acceleration, Newton iterations."""
    ops.timeSeries("Path", 1, "-dt", record["time_step"], "-filePath", record_path(record))
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", NEWTON_TOLERANCE, NEWTON_ITERATIONS)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def record_path(record):
    """The record's file, beside this script."""
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), record["file"])


class Watch:
    """Each contact's largest force and its impacts over a record's committed steps (lists in CONTACTS' order)."""

    def __init__(self, ops):
        self.ops = ops
        self.nodes = [contact_nodes(contact) for contact in CONTACTS]
        self.force_max = [0.0] * len(CONTACTS)
        self.impacts = [0] * len(CONTACTS)
        self.penetration = [-contact["gap"] for contact in CONTACTS]

    def observe(self):
        """After a committed step, at each contact: the penetration delta = x_left - x_right - gap (an impact
        begins where it turns positive, as pounding counts them) and the contact force, the material's stress
        negated."""
        ops = self.ops
        for index, (contact, (left, right)) in enumerate(zip(CONTACTS, self.nodes)):
            penetration = ops.nodeDisp(left, 1) - ops.nodeDisp(right, 1) - contact["gap"]
            if penetration > 0.0:
                if self.penetration[index] <= 0.0:
                    self.impacts[index] += 1
                force = -ops.eleResponse(CONTACT_TAGS + index + 1, "material", 1, "stress")[0]
                self.force_max[index] = max(self.force_max[index], force)
            self.penetration[index] = penetration


def advance(ops, step, watch, tally, cuts=0):
    """One step of ``step`` [s]: Newton, then the fallback algorithms, then two half steps (recursively).
    Returns False when even the smallest step fails."""
    if ops.analyze(1, step) == 0:
        watch.observe()
        return True
    for algorithm in FALLBACK_ALGORITHMS:
        ops.algorithm(*algorithm)
        ops.test("NormDispIncr", NEWTON_TOLERANCE, FALLBACK_ITERATIONS)
        converged = ops.analyze(1, step) == 0
        ops.algorithm("Newton")
        ops.test("NormDispIncr", NEWTON_TOLERANCE, NEWTON_ITERATIONS)
        if converged:
            tally[algorithm[0]] = tally.get(algorithm[0], 0) + 1
            watch.observe()
            return True
    if cuts == MOST_STEP_CUTS:
        return False
    tally["step cuts"] = tally.get("step cuts", 0) + 1
    return advance(ops, step / 2, watch, tally, cuts + 1) and advance(ops, step / 2, watch, tally, cuts + 1)


def run_record(ops, record, step):
    """F_max [N] and the impacts, over all contacts and at each (``contacts``: lists in CONTACTS' order), the CPU
    time [s], the fallbacks used and whether it completed."""
    start = time.process_time()
    build_model(ops)
    set_up_analysis(ops, record)
    duration = (record["samples"] - 1) * record["time_step"]
    steps = max(1, math.ceil(duration / step - 1e-9))
    watch, tally = Watch(ops), {}
    completed = all(advance(ops, duration / steps, watch, tally) for _ in range(steps))
    return {"force_max": max(watch.force_max), "impacts": sum(watch.impacts), "cpu_seconds": time.process_time() - start,
            "contacts": {"force_max": watch.force_max, "impacts": watch.impacts},
            "fallbacks": tally, "completed": completed, "time": ops.getTime()}


def describe_contact(contact):
    """A contact in words, as pounding writes it: "buildings 1-2, floors 3/2"."""
    (left, right), (level_left, level_right) = contact["between"], contact["levels"]
    return f"buildings {left}-{right}, floors {level_left}/{level_right}"


def governing(result):
    """Where a record's F_max is, when there are several contacts: ", at buildings 1-2, floors 3/2"."""
    forces = result["contacts"]["force_max"]
    if len(CONTACTS) == 1 or max(forces) <= 0.0:
        return ""
    return f" at {describe_contact(CONTACTS[forces.index(max(forces))])}"


def arguments():
    """The script's command-line options."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--step", type=float, default=TIME_STEP, help=f"analysis step [s] (default {TIME_STEP:g}, see TIME_STEP)")
    parser.add_argument("--records", type=int, default=len(RECORDS), help="run the first N records only")
    parser.add_argument("--check-step", action="store_true",
                        help="also run the first record at half the step and print how much F_max moves")
    parser.add_argument("--log", default=os.devnull,
                        help="file for OpenSees' own messages (default: none; each impact is announced there)")
    return parser.parse_args()


def main():
    """Run the records; print a line for each, then the JSON summary; 1 when a record failed, else 0."""
    options = arguments()
    if not options.step > 0 or not 1 <= options.records <= len(RECORDS):
        sys.exit(f"model.py: --step must be > 0 s and --records in 1..{len(RECORDS)}")
    ops = import_opensees()
    ops.logFile(options.log, "-noEcho")
    results, failed, tally = [], [], {}
    for record in RECORDS[:options.records]:
        result = run_record(ops, record, options.step)
        for name, count in result["fallbacks"].items():
            tally[name] = tally.get(name, 0) + count
        used = ", ".join(f"{name} {count}" for name, count in sorted(result["fallbacks"].items())) or "none"
        status = "" if result["completed"] else f"  FAILED at t = {result['time']:.4f} s"
        print(f"{record['name']}: F_max {result['force_max'] / 1e3:.3f} kN{governing(result)}, {result['impacts']} impacts, "
              f"{result['cpu_seconds']:.2f} s CPU, fallbacks: {used}{status}", flush=True)
        results.append(result)
        if not result["completed"]:
            failed.append(record["name"])
    summary = {
        "case": CASE_NAME,
        "records": [record["name"] for record in RECORDS[:options.records]],
        "force_max": [result["force_max"] if result["completed"] else None for result in results],
        "impacts": [result["impacts"] for result in results],
        "contacts": [{"between": contact["between"], "levels": contact["levels"],
                      "force_max": [result["contacts"]["force_max"][index] if result["completed"] else None for result in results],
                      "impacts": [result["contacts"]["impacts"][index] for result in results]}
                     for index, contact in enumerate(CONTACTS)],
        "cpu_seconds": [result["cpu_seconds"] for result in results],
        "time_step": options.step,
        "fallbacks": tally,
        "failed": failed,
        "units": {"force": "N", "time": "s"},
    }
    used = ", ".join(f"{name} {count}" for name, count in sorted(tally.items()))
    print(f"over {len(results)} records, steps where Newton failed and a fallback converged, and step halvings: {used or 'none'}"
          + (f"; {len(failed)} record(s) FAILED (force_max null)" if failed else ""))
    if options.check_step and results[0]["completed"]:
        half = run_record(ops, RECORDS[0], options.step / 2)
        change = half["force_max"] / results[0]["force_max"] - 1.0 if results[0]["force_max"] > 0 else 0.0
        if not half["completed"]:
            change = None
            print(f"step check: {RECORDS[0]['name']} FAILED at half the step, t = {half['time']:.4f} s")
        else:
            print(f"step check, {RECORDS[0]['name']}: F_max {results[0]['force_max'] / 1e3:.3f} kN at {options.step:g} s, "
                  f"{half['force_max'] / 1e3:.3f} kN at {options.step / 2:g} s: {100 * change:+.3f} %")
        summary["step_check"] = {"force_max_half_step": half["force_max"] if half["completed"] else None, "relative_change": change}
    print(json.dumps(summary))
    return 1 if failed else 0

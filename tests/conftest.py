"""Shared helpers for the tests: small cases built in code, SI units."""

import numpy as np
import pytest

from pounding import BoucWen, Building, Case, Contact, Excitation, KanaiTajimi, Storey

KANAI_TAJIMI_SI = KanaiTajimi(G0=65.03e-4, omega_g=27.02, xi_g=0.34)  # the paper's ground, in SI


def one_storey(period: float, mass: float = 4.0e4, bouc_wen: BoucWen | None = None, damping_ratio: float = 0.05) -> Building:
    stiffness = mass * (2 * np.pi / period) ** 2
    return Building((Storey(mass, stiffness, bouc_wen or BoucWen(alpha=1.0)),), damping_ratio=damping_ratio)


def make_case(buildings, gap=0.01, stiffness=2e9, restitution=0.65, levels=(1, 1), model="jankowski",
              spectrum=KANAI_TAJIMI_SI, duration=20.0, envelope=None, time_step=0.005) -> Case:
    return Case(
        excitation=Excitation(spectrum, duration, envelope, time_step=time_step),
        buildings=tuple(buildings),
        contacts=Contact(gap=gap, stiffness=stiffness, restitution=restitution, levels=levels, model=model),
        name="test",
    )


@pytest.fixture
def paper_bouc_wen() -> BoucWen:
    """Section 5's storey law in SI: beta = 2 /cm, gamma = -1 /cm."""
    return BoucWen(alpha=0.05, A=1.0, beta=200.0, gamma=-100.0, n=1.0)


# Browser fixtures (headless Debian Chromium, the dashboard served on a free port),
# defined once here so the session-scoped browser is shared by every module.
from tests.browser import browser, dashboard, dashboard_url  # noqa: E402,F401


_BROWSER_FIXTURES = {"browser", "dashboard", "dashboard_url"}


def pytest_collection_modifyitems(config, items):
    """A test that drives Chromium is marked ``browser`` by the fixtures it takes, whether or not its module says so:
    ``-m "not browser"`` (the README's fast subset) leaves out every one."""
    for item in items:
        if _BROWSER_FIXTURES & set(getattr(item, "fixturenames", ())) and not item.get_closest_marker("browser"):
            item.add_marker(pytest.mark.browser)

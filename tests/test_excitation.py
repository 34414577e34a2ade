"""Generated records against the spectrum they are drawn from."""

import math

import numpy as np
import pytest
from scipy import integrate, signal

from pounding import CloughPenzien, Excitation, KanaiTajimi, ShinozukaSato
from pounding.hazard.excitation import ground_acceleration, ground_accelerations, record_rng

from .conftest import KANAI_TAJIMI_SI


def test_kanai_tajimi_variance_is_the_integral_of_eq7():
    numeric, _ = integrate.quad(KANAI_TAJIMI_SI.psd, -np.inf, np.inf, limit=400)
    assert KANAI_TAJIMI_SI.variance() == pytest.approx(numeric, rel=1e-6)


def test_clough_penzien_removes_low_frequencies():
    spectrum = CloughPenzien(G0=1e-3, omega_g=15.0, xi_g=0.6, omega_f=1.5, xi_f=0.6)
    base = KanaiTajimi(G0=1e-3, omega_g=15.0, xi_g=0.6)
    assert spectrum.psd(np.array([0.0]))[0] == 0.0
    assert spectrum.psd(np.array([50.0]))[0] == pytest.approx(base.psd(np.array([50.0]))[0], rel=0.01)
    assert spectrum.variance() < base.variance()


@pytest.mark.parametrize("envelope", [None, ShinozukaSato()])
def test_same_seed_same_record_independent_of_batch(envelope):
    excitation = Excitation(KANAI_TAJIMI_SI, 10.0, envelope)
    batch = ground_accelerations(excitation, seed=7, indices=range(6))
    again = ground_accelerations(excitation, seed=7, indices=[4, 5])
    np.testing.assert_array_equal(batch[4:], again)
    assert not np.allclose(batch[0], batch[1])
    other_seed = ground_accelerations(excitation, seed=8, indices=[0])
    assert not np.allclose(batch[0], other_seed[0])


def test_record_variance_equals_the_integral_of_the_spectrum():
    excitation = Excitation(KANAI_TAJIMI_SI, 20.0)
    # The generator keeps frequencies up to the cutoff; that band's integral:
    band, _ = integrate.quad(KANAI_TAJIMI_SI.psd, 0.0, excitation.cutoff_frequency, limit=400)
    assert excitation.represented_variance() == pytest.approx(2 * band, rel=0.01)
    # ... and at least 97 % of the whole spectrum's variance.
    assert excitation.represented_variance() > 0.97 * KANAI_TAJIMI_SI.variance()
    records = ground_accelerations(excitation, seed=1, indices=range(400))
    per_record = records.var(axis=1)
    standard_error = per_record.std(ddof=1) / math.sqrt(per_record.size)
    assert abs(per_record.mean() - 2 * band) < 4 * standard_error
    assert per_record.mean() == pytest.approx(2 * band, rel=0.03)
    # Gaussian: kurtosis 3 within sampling error.
    pooled = (records / records.std()).ravel()
    assert np.mean(pooled**4) == pytest.approx(3.0, abs=0.05)


def test_welch_psd_follows_kanai_tajimi():
    excitation = Excitation(KANAI_TAJIMI_SI, 40.0)
    records = ground_accelerations(excitation, seed=2, indices=range(60))
    frequency, one_sided = signal.welch(records, fs=1 / excitation.time_step, nperseg=1024, axis=-1)
    mean_psd = one_sided.mean(axis=0)
    omega = 2 * np.pi * frequency
    # Welch gives a one-sided PSD per Hz; the two-sided PSD per rad/s is that / (4 pi).
    measured = mean_psd / (4 * np.pi)
    expected = KANAI_TAJIMI_SI.psd(omega)
    band = (omega > 3.0) & (omega < 0.8 * excitation.cutoff_frequency)
    ratio = measured[band] / expected[band]
    # 60 records x ~15 Welch segments each: a few % of scatter per bin.
    assert np.median(ratio) == pytest.approx(1.0, abs=0.03)
    assert np.all(np.abs(ratio - 1) < 0.2)
    above = omega > 1.1 * excitation.cutoff_frequency
    assert np.all(measured[above] < 0.01 * expected[above])


def test_shinozuka_sato_envelope_peaks_at_one():
    envelope = ShinozukaSato(0.085, 0.17)
    t = np.linspace(0, 60, 600_001)
    values = envelope(t)
    assert values.max() == pytest.approx(1.0, abs=1e-9)
    assert t[values.argmax()] == pytest.approx(math.log(2) / 0.085, abs=1e-3)
    assert values[0] == 0.0


def test_non_stationary_records_follow_the_envelope():
    envelope = ShinozukaSato()
    excitation = Excitation(KANAI_TAJIMI_SI, 40.0, envelope)
    records = ground_accelerations(excitation, seed=3, indices=range(300))
    times = excitation.times()
    late = (times > 30) & (times < 32)
    peak = np.abs(times - envelope.peak_time) < 1.0
    ratio = records[:, late].std() / records[:, peak].std()
    expected = envelope(times[late]).mean() / envelope(times[peak]).mean()
    assert ratio == pytest.approx(expected, rel=0.1)


def test_record_rng_is_a_child_of_the_seed_sequence():
    child = np.random.SeedSequence(11).spawn(4)[3]
    assert np.random.default_rng(child).random() == record_rng(11, 3).random()
    single = ground_acceleration(Excitation(KANAI_TAJIMI_SI, 5.0), record_rng(11, 3))
    assert single.shape == (Excitation(KANAI_TAJIMI_SI, 5.0).n_samples,)


@pytest.mark.parametrize("factor", [1, 8])
def test_a_larger_synthesis_factor_keeps_the_lowest_frequencies(factor):
    """The mean of a record over its duration T has variance
    int S(w) (sin(w T / 2) / (w T / 2))^2 dw, most of it from w < 2 pi / T.
    Records periodic over about T (factor 1) lose that band; with factor 8
    the synthesis grid is 8 times finer and the variance is kept."""
    from pounding.hazard.excitation import _one_sided_weights

    excitation = Excitation(KANAI_TAJIMI_SI, 20.0, synthesis_factor=factor)
    duration = (excitation.n_samples - 1) * excitation.time_step

    def kernel(w):
        return np.sinc(w * duration / (2 * np.pi)) ** 2  # numpy's sinc is sin(pi x) / (pi x)

    expected, _ = integrate.quad(lambda w: 2 * KANAI_TAJIMI_SI.psd(w) * kernel(w), 0.0, 50.0, limit=400, points=[2 * np.pi / duration])
    # What the synthesis grid itself represents (each frequency's variance times the kernel):
    omega = excitation.synthesis_frequencies()
    represented = np.sum(_one_sided_weights(excitation) * kernel(omega))
    records = ground_accelerations(excitation, seed=3, indices=range(400))
    # The trapezoid mean over the record, as its integral over [0, T] / T.
    means = np.trapezoid(records, dx=excitation.time_step, axis=1) / duration
    assert np.var(means) == pytest.approx(represented, rel=0.25)
    if factor == 1:
        assert represented < 0.1 * expected
    else:
        # Short by about 1 / factor: the zero-frequency bin is left out.
        assert expected * (1 - 1.5 / factor) < represented < expected


def test_synthesis_factor_is_validated():
    from pounding.errors import CaseError

    with pytest.raises(CaseError, match="synthesis_factor"):
        Excitation(KANAI_TAJIMI_SI, 20.0, synthesis_factor=0)

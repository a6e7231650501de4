"""Time series from a one-sided spectrum by the random-phase method: at the frequencies
f_k = k / (N dt), k = 1 ... N/2 - 1, of a record of N samples dt apart, the amplitudes
a_k = sqrt(2 S(f_k) df), df = 1 / (N dt), and phases phi_k uniform on [0, 2 pi) from the case's
generator give x(t_n) = sum_k a_k cos(2 pi f_k t_n + phi_k) by one inverse FFT (Shinozuka and
Deodatis 1991; DNV-RP-C205 3.5.11 for waves): its variance is sum_k a_k^2 / 2 = int S df and its
periodogram is S at each f_k. The record is periodic with period N dt.

:class:`Record` holds a case's series side by side on one time grid and gives their values at a
time by linear interpolation (one row per step, however many series).
"""

from __future__ import annotations

import math

import numpy as np


def grid(duration: float, step: float) -> tuple[int, float]:
    """(N, df): the smallest power of two N of samples ``step`` [s] apart covering ``duration``."""
    if not (math.isfinite(duration) and duration > 0.0 and math.isfinite(step) and step > 0.0):
        raise ValueError(f"a record needs a duration and a step > 0, not {duration!r}, {step!r}")
    n = 1 << max(4, math.ceil(math.log2(duration / step)))
    return n, 1.0 / (n * step)


def amplitudes(spectrum: np.ndarray, df: float, generator: np.random.Generator) -> np.ndarray:
    """Complex amplitudes a_k exp(i phi_k) of one-sided ``spectrum`` values at f_k = k df
    (k = 0 ... N/2), the mean (k 0) and the Nyquist term (k N/2) left out."""
    values = np.sqrt(2.0 * np.asarray(spectrum, dtype=float) * df)
    values[0] = values[-1] = 0.0
    return values * np.exp(1j * generator.uniform(0.0, 2.0 * math.pi, values.size))


def real_series(coefficients: np.ndarray, n: int) -> np.ndarray:
    """x_n = sum_k Re(c_k exp(2 pi i k n / N)) of the N/2 + 1 complex amplitudes ``c_k``."""
    return np.fft.irfft(coefficients * (n / 2.0), n)


def analytic_series(coefficients: np.ndarray, n: int) -> np.ndarray:
    """z_n = sum_k c_k exp(2 pi i k n / N), whose real part is :func:`real_series`."""
    full = np.zeros(n, dtype=complex)
    full[:coefficients.size] = coefficients
    return np.fft.ifft(full) * n


class Record:
    """Series ``columns`` (one per name) sampled every ``step`` [s] from t = 0, periodic."""

    def __init__(self, step: float, columns: dict[str, np.ndarray]):
        self.step = step
        self.names = tuple(columns)
        self.index = {name: i for i, name in enumerate(self.names)}
        data = np.column_stack([np.asarray(columns[name], dtype=float) for name in self.names])
        self.data = np.vstack([data, data[:1]])                  # the first sample again: periodic
        self.samples = data.shape[0]

    def at(self, t: float) -> np.ndarray:
        """Every series at time ``t`` [s], linear between samples."""
        position = (t / self.step) % self.samples
        i = int(position)
        w = position - i
        return self.data[i] * (1.0 - w) + self.data[i + 1] * w

#!/usr/bin/python3
"""The thin film's reflectance at normal incidence for test_pbr's
thin_film_matches_the_airy_spectrum, computed without the shader's series:
the exact Airy reflectance of the film per wavelength (complex amplitudes),
integrated against the CIE 1931 matching functions (Wyman, Sloan and
Shirley's 2013 multi-lobe fit), to linear Rec. 709.  As the shader (and
Belcour and Barla's model) does, the spectrum's mean, the incoherent sum
R12 + T^2 R23 / (1 - R12 R23), is kept as a grey and only the
interference around it goes through the matching functions.

Run with Debian's python3 (numpy); prints one C initializer per case."""
import numpy as np


def lobe(lam, mu, s1, s2):
    s = np.where(lam < mu, s1, s2)
    return np.exp(-0.5 * ((lam - mu) / s) ** 2)


def cmf(lam):
    x = (1.056 * lobe(lam, 599.8, 37.9, 31.0) + 0.362 * lobe(lam, 442.0, 16.0, 26.7)
         - 0.065 * lobe(lam, 501.1, 20.4, 26.2))
    y = 0.821 * lobe(lam, 568.8, 46.9, 40.5) + 0.286 * lobe(lam, 530.9, 16.3, 31.1)
    z = 1.217 * lobe(lam, 437.0, 11.8, 36.0) + 0.681 * lobe(lam, 459.0, 26.0, 13.8)
    return np.stack([x, y, z])


XYZ_TO_709 = np.array([[3.2404542, -1.5371385, -0.4985314],
                       [-0.9692660, 1.8760108, 0.0415560],
                       [0.0556434, -0.2040259, 1.0572252]])


def film(thickness, n2, f0):
    lam = np.arange(300.0, 900.0, 0.25)
    out = []
    for f in f0:
        s = np.sqrt(min(max(f, 0.0), 0.9999))
        n3 = (1 + s) / (1 - s)
        r12 = (1 - n2) / (1 + n2)
        r23 = (n2 - n3) / (n2 + n3)
        e = np.exp(1j * 4 * np.pi * n2 * thickness / lam)
        refl = np.abs((r12 + r23 * e) / (1 + r12 * r23 * e)) ** 2
        R12, R23 = r12 ** 2, r23 ** 2
        mean = R12 + (1 - R12) ** 2 * R23 / (1 - R12 * R23)
        c = cmf(lam)
        xyz = (c * (refl - mean)).sum(axis=1) / c[1].sum()
        out.append(mean + XYZ_TO_709 @ xyz)
    # Channel k of the base's F0 k.
    return [out[k][k] for k in range(3)]


CASES = [(400.0, 1.3, (0.04, 0.04, 0.04)), (250.0, 1.33, (0.0, 0.0, 0.0)),
         (300.0, 1.8, (0.04, 0.04, 0.04)), (550.0, 1.5, (0.9, 0.6, 0.3))]

if __name__ == "__main__":
    for t, n, f0 in CASES:
        r = film(t, n, f0)
        print("{ %.1ff, %.2ff, { %.2ff, %.2ff, %.2ff }, { %.4f, %.4f, %.4f } }," %
              (t, n, *f0, *r))

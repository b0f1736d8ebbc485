"""Sobol' points and their Owen scrambling, in numpy: the reference that the GLSL of
shaders/terms/sampling.glsl (lab_sobol, lab_owen) is tested against.

Dimension 0 is the van der Corput sequence (bit reversal); dimensions 1 and 2 use the
primitive polynomials x + 1 and x^2 + x + 1 with initial numbers m = (1) and (1, 3), as in
Joe and Kuo, "Constructing Sobol sequences with better two-dimensional projections"
(SIAM J. Sci. Comput. 30, 2008). Points are taken in index order (not Gray code), so every
prefix of 2^m points is a (0, m, 2)-net in dimensions 0 and 1.
"""

from __future__ import annotations

import numpy as np

BITS = 32
# (degree s, coefficients a, initial m_1..m_s) of each dimension after the first
POLYNOMIALS = ((1, 0, (1,)), (2, 1, (1, 3)))


def direction_numbers(s: int, a: int, m_init: tuple[int, ...]) -> list[int]:
    """The 32 direction numbers v_k = m_k 2^(32 - k) of one Sobol' dimension (Bratley and
    Fox's recurrence: m_k = 2 a_1 m_(k-1) ^ 4 a_2 m_(k-2) ^ ... ^ 2^s m_(k-s) ^ m_(k-s))."""
    m = list(m_init)
    for k in range(s, BITS):
        value = m[k - s] ^ (m[k - s] << s)
        for j in range(1, s):
            if (a >> (s - 1 - j)) & 1:
                value ^= m[k - j] << j
        m.append(value)
    return [(m[k] << (BITS - 1 - k)) & 0xFFFFFFFF for k in range(BITS)]


def generators() -> list[list[int]]:
    """Direction numbers of dimensions 0, 1 and 2 (32 each)."""
    first = [1 << (BITS - 1 - k) for k in range(BITS)]
    return [first, *(direction_numbers(*p) for p in POLYNOMIALS)]


def sobol(index: np.ndarray, dim: int) -> np.ndarray:
    """32-bit Sobol' integers of `index` (uint) in dimension `dim`."""
    index = np.asarray(index, np.uint64)
    out = np.zeros(index.shape, np.uint64)
    for k, v in enumerate(generators()[dim]):
        out ^= np.where((index >> np.uint64(k)) & np.uint64(1), np.uint64(v), np.uint64(0))
    return out.astype(np.uint32)


def reverse_bits(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, np.uint32).copy()
    for shift, mask in ((1, 0x55555555), (2, 0x33333333), (4, 0x0F0F0F0F), (8, 0x00FF00FF)):
        m = np.uint32(mask)
        x = ((x >> np.uint32(shift)) & m) | ((x & m) << np.uint32(shift))
    return (x >> np.uint32(16)) | (x << np.uint32(16))


def owen(x: np.ndarray, seed: int) -> np.ndarray:
    """Nested uniform (Owen) scrambling of 32-bit fractions by a hash: reversed, each bit
    is flipped by a function of the bits below it only (a Laine-Karras style permutation
    of additions and multiplications by even constants), then reversed back (Burley,
    "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020)."""
    with np.errstate(over="ignore"):
        r = reverse_bits(x).astype(np.uint32)
        r = r + np.uint32(seed & 0xFFFFFFFF)
        for c in (0x6C50B47C, 0xB82F1E52, 0xC7AFE638, 0x8D22F6E6):
            r ^= r * np.uint32(c)
    return reverse_bits(r)


def glsl_constants() -> str:
    """The GLSL array of dimensions 1 and 2's direction numbers (as sampling.glsl has it)."""
    rows = []
    for dim in (1, 2):
        numbers = generators()[dim]
        for start in range(0, BITS, 8):
            rows.append("    " + ", ".join(f"0x{v:08x}u" for v in numbers[start : start + 8]))
    return "const uint LAB_SOBOL_V[64] = uint[64](\n" + ",\n".join(rows) + ");"

"""The part-wide plate figures of a volume read block by block, one block's pair lengths at a time.

The first pass (:func:`~medialaxis.volume.blockwise.blocks.scan_block`) leaves each
block's plate-crossing pair lengths in its spill file: 8 bytes a pair, about
120 MB at 2048^3 and four times that at 4096^3, too many for the client to
gather. :func:`block_plates` gives what
:func:`~medialaxis.volume.plates.plate_summary` and
:func:`~medialaxis.volume.plates.nominal_thicknesses` give on all of them,
bit for bit, reading one block's at a time:

* the histogram of the nominal thicknesses adds up the blocks' histograms
  over the bins that the smallest and largest length fix;
* the median is the middle length(s) found by radix selection on the
  lengths' bits: non-negative IEEE 754 doubles order as their bit patterns
  do as unsigned integers, so four passes of 16-bit digit counts find the
  k-th smallest exactly (Knuth, The Art of Computer Programming, Vol. 3:
  Sorting and Searching, 2nd ed., Addison-Wesley, 1998, section 5.2.5; IEEE
  Standard for Floating-Point Arithmetic, IEEE Std 754-2019, section 5.10,
  doi:10.1109/IEEESTD.2019.8766229).

Memory: one block's lengths and 65,536 counts, whatever the volume's size.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence

import numpy as np

from medialaxis.volume.blockwise.blocks import BlockScan
from medialaxis.volume.plates import PlateThickness, nominal_edges, nominal_peaks, plate_summary

__all__ = ["block_plates", "kth_smallest"]

#: Bits of the radix digit of each selection pass (four passes over a double's 64 bits).
DIGIT_BITS = 16


def _bits(values: np.ndarray) -> np.ndarray:
    """The bit patterns of non-negative doubles, ordered as the doubles are (-0.0 taken as 0.0)."""
    return (np.asarray(values, np.float64) + 0.0).view(np.uint64)


def kth_smallest(parts: Callable[[], Iterable[np.ndarray]], k: int) -> float:
    """The ``k``-th smallest (from 0) of the non-negative doubles that ``parts()`` yields, part by part.

    ``parts`` is called once per pass (``64 / DIGIT_BITS`` passes) and must yield the same values each time.
    """
    prefix, rank, known = 0, int(k), 0
    for shift in range(64 - DIGIT_BITS, -1, -DIGIT_BITS):
        counts = np.zeros(1 << DIGIT_BITS, np.int64)
        for values in parts():
            bits = _bits(values)
            if known:  # only the values whose higher digits are the ones chosen so far
                bits = bits[(bits >> (shift + DIGIT_BITS)) == prefix]
            digits = ((bits >> shift) & ((1 << DIGIT_BITS) - 1)).astype(np.intp)
            counts += np.bincount(digits, minlength=1 << DIGIT_BITS)
        below = np.cumsum(counts)
        if rank >= below[-1]:
            raise IndexError(f"k={k} is not below the number of values, {int(below[-1]) + k - rank}")
        digit = int(np.searchsorted(below, rank, side="right"))
        rank -= int(below[digit - 1]) if digit else 0
        prefix, known = (prefix << DIGIT_BITS) | digit, known + DIGIT_BITS
    return float(np.array(prefix, np.uint64).view(np.float64))


def _lengths(scans: Sequence[BlockScan], lower: float, upper: float) -> Iterator[np.ndarray]:
    """Each block's pair lengths within ``[lower, upper]`` (one block's in memory at a time)."""
    for scan in scans:
        gaps = scan.plate_gaps()
        if len(gaps):
            yield gaps[(gaps >= lower) & (gaps <= upper)]


def _middle(scans: Sequence[BlockScan], lower: float, upper: float, count: int) -> np.ndarray:
    """The middle length (odd ``count``) or the two middle ones of the ``count`` lengths in ``[lower, upper]``."""
    k = (count - 1) // 2
    first = kth_smallest(lambda: _lengths(scans, lower, upper), k)
    if count % 2:
        return np.array([first])
    at_most, above = 0, np.inf
    for values in _lengths(scans, lower, upper):
        at_most += int(np.count_nonzero(values <= first))
        above = min(above, float(values[values > first].min(initial=np.inf)))
    return np.array([first, first if at_most >= k + 2 else above])


def block_plates(scans: Sequence[BlockScan], lower: float, upper: float,
                 unit: float) -> tuple[PlateThickness, np.ndarray]:
    """``(plate_summary(gaps, ...), nominal_thicknesses(gaps, ...))`` of the blocks' gaps, one block's at a time.

    Raises
    ------
    EmptyShapeError
        If no plate has a thickness in ``[lower, upper]`` (as :func:`~medialaxis.volume.plates.plate_summary`).
    """
    count = inside = 0
    least = most = shortest = longest = np.nan
    for scan in scans:
        gaps = scan.plate_gaps()
        if not len(gaps):
            continue
        count += len(gaps)
        least, most = np.fmin(least, gaps.min()), np.fmax(most, gaps.max())
        thick = gaps[gaps >= lower]
        inside += int(np.count_nonzero(thick <= upper))
        if len(thick):
            shortest, longest = np.fmin(shortest, thick.min()), np.fmax(longest, thick.max())
    if not inside:
        # the smallest and largest lengths give the refusal all of them give (it names only those two)
        plate_summary(np.array([least, most]) if count else np.zeros(0), lower, upper, unit)
    # the median of the middle length(s) is the median of all the lengths inside
    plates = plate_summary(_middle(scans, lower, upper, inside), lower, upper, unit)
    edges = nominal_edges(float(shortest), float(longest), unit)
    counts = np.zeros(len(edges) - 1, np.int64)
    for scan in scans:
        gaps = scan.plate_gaps()
        counts += np.histogram(gaps[gaps >= lower], edges)[0]
    return plates, nominal_peaks(counts, edges, unit)

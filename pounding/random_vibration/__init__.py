"""Random vibration of Gaussian processes, the layer every estimate stands on: expected peaks and peak factors
(Davenport, Eq. 23-24; Vanmarcke; Michaelov's moments, Eq. 29), and the compiled counts of crossings and peaks.

Modules: :mod:`.peaks` (Davenport's peak factor, Michaelov's variance), :mod:`.peak_factors` (Vanmarcke's
barrier crossings: expected peaks of a process and of an oscillator's response), :mod:`.crossing_kernels`
(the compiled crossing, clump and peak counts). Imports nothing of the package above the basics.
"""

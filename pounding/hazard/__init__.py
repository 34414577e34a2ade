"""The hazard: the ground motion a case is shaken by, as a random process, a design spectrum or recorded motions.

Modules: :mod:`.excitation` (Kanai-Tajimi and Clough-Penzien spectra, envelopes, seeded records),
:mod:`.filter_bank` (a bank of band-pass filtered white noises), :mod:`.design_spectra` (elastic design spectra
of the codes), :mod:`.compatible_psd` (a PSD compatible with a design spectrum), :mod:`.accelerograms` (reading
and writing records), :mod:`.motion_fit` (a Kanai-Tajimi or Clough-Penzien spectrum describing a suite of records),
:mod:`.suite_spectrum` (the filter bank and envelope the closed form takes for a suite), :mod:`.fit_quality`
(how faithfully: expected against recorded Sa and PGA), :mod:`.response_spectra`
(response spectra of records), :mod:`.sources` (a design spectrum or recorded motions as a case's source).
"""

"""The hazard: the ground motion a case is shaken by, as a random process, a design spectrum or recorded motions.

Modules: :mod:`.excitation` (Kanai-Tajimi and Clough-Penzien spectra, envelopes, seeded records),
:mod:`.filter_bank` (a bank of band-pass filtered white noises), :mod:`.design_spectra` (elastic design spectra
of the codes), :mod:`.compatible_psd` (a PSD compatible with a design spectrum), :mod:`.accelerograms` (reading
and writing records), :mod:`.motion_fit` (a spectrum fitted to a suite of records), :mod:`.response_spectra`
(response spectra of records), :mod:`.sources` (a design spectrum or recorded motions as a case's source).
"""

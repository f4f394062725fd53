"""Thin-film interference colours: media, optics, colours and thickness-map pictures.

Modules: :mod:`.media` (refractive indices), :mod:`.optics` (two-beam, Airy, transfer
matrices), :mod:`.films` (soap film, oil on water, film on glass), :mod:`.colour` (colours
under a light), :mod:`.maps` (thickness maps through a lookup table), :mod:`.zawischa`
(seed 000's strip). Import the modules you need; nothing heavy is imported here.
"""

"""How different a set of haptic icons feels: a perceptual distance and a 2-D map (MDS).

No Qt here; `haptic-timeline compare` and the editor's map read the same numbers.
"""

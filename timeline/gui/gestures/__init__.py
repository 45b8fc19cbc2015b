"""Mouse gestures on the timeline, one small class each; a drag is one undo step.

A gesture starts from the project as it was at the press and, on every move, applies one edit
to that starting state with a merge key unique to the drag, so the history keeps a single step.
"""

"""Undo/redo over project states; a drag merges its steps into one entry.

Variants are the designer's saved alternatives, so moving through the history never loses one:
undo, redo and a jump arrive at a step's state with every variant still alive added to it (only
a step that deleted a variant removes it, when it is redone).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

from timeline.edits.step_names import step_name
from timeline.edits.variants import kept_across, removed_names
from timeline.model import Project, Variant


@dataclass(frozen=True)
class Step:
    """One entry: the state after an action, its label, and a key that later steps may merge on.

    `label` is the caller's ("move clip"); `name` says what changed ("move 'tap' to 20°"),
    worked out from the state before when first asked for.
    """

    project: Project
    label: str
    merge_key: object = None
    removed: frozenset[str] = frozenset()  # the variants this step deleted
    before: Project | None = field(default=None, repr=False, compare=False)
    described: str = ""  # the name, once known (kept when the step's variants are carried)

    @cached_property
    def name(self) -> str:
        return self.described or step_name(self.label, self.before, self.project)


class History:
    """A linear undo history of immutable project states, with a clean (saved) mark."""

    def __init__(self, project: Project) -> None:
        self._steps: list[Step] = [Step(project, "open")]
        self._index = 0
        self._clean: int | None = 0

    @property
    def project(self) -> Project:
        return self._steps[self._index].project

    def do(self, label: str, project: Project, merge_key: object = None) -> Project:
        """Record a new state; with the same non-None merge_key as the last step, replace it."""
        del self._steps[self._index + 1 :]
        if self._clean is not None and self._clean > self._index:
            self._clean = None
        top = self._steps[self._index]
        if merge_key is not None and top.merge_key == merge_key and self._index > 0:
            if self._clean == self._index:
                self._clean = None
            before = self._steps[self._index - 1].project
            step = Step(project, label, merge_key, removed_names(before, project), before)
            self._steps[self._index] = step
        else:
            step = Step(project, label, merge_key, removed_names(top.project, project), top.project)
            self._steps.append(step)
            self._index += 1
        return project

    def undo(self) -> Project:
        if self.can_undo:
            self._arrive(self._index - 1)
        return self.project

    def redo(self) -> Project:
        if self.can_redo:
            self._arrive(self._index + 1)
        return self.project

    @property
    def can_undo(self) -> bool:
        return self._index > 0

    @property
    def can_redo(self) -> bool:
        return self._index < len(self._steps) - 1

    @property
    def undo_label(self) -> str:
        return self._steps[self._index].label if self.can_undo else ""

    @property
    def redo_label(self) -> str:
        return self._steps[self._index + 1].label if self.can_redo else ""

    @property
    def labels(self) -> list[str]:
        """Every step's label, oldest first (the first is "open")."""
        return [step.label for step in self._steps]

    @property
    def names(self) -> list[str]:
        """Every step's name (what it changed), oldest first."""
        return [step.name for step in self._steps]

    @property
    def undo_name(self) -> str:
        """What undo takes back, by name ("" at the first step)."""
        return self._steps[self._index].name if self.can_undo else ""

    @property
    def redo_name(self) -> str:
        return self._steps[self._index + 1].name if self.can_redo else ""

    @property
    def index(self) -> int:
        """Which step the project is at."""
        return self._index

    def go_to(self, index: int) -> Project:
        """Jump to a step (undoing or redoing every step in between)."""
        if not 0 <= index < len(self._steps):
            raise IndexError(f"there is no step {index}")
        self._arrive(index)
        return self.project

    def _arrive(self, index: int) -> None:
        """Move to a step, carrying the variants alive now (see the module's docstring)."""
        shown, step = self.project, self._steps[index]
        removed: set[str] = set()
        restored: dict[str, Variant] = {}
        if index > self._index:
            for passed in self._steps[self._index + 1 : index + 1]:
                removed |= passed.removed
        else:
            for k in range(self._index, index, -1):
                before = self._steps[k - 1].project
                for name in self._steps[k].removed:
                    restored.update({v.name: v for v in before.variants if v.name == name})
        project = kept_across(shown, step.project, frozenset(removed), restored)
        if project is not step.project:
            self._steps[index] = replace(step, project=project, described=step.name)
            if self._clean == index:
                self._clean = None  # the saved file lacks the variants carried here
        self._index = index

    def mark_clean(self) -> None:
        """Remember the current state as saved."""
        self._clean = self._index

    @property
    def modified(self) -> bool:
        return self._clean != self._index

    def __len__(self) -> int:
        return len(self._steps)

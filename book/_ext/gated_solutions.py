"""Hide gated solutions in the student edition (``make book-student``).

A solution that computes its answer is written as ``{solution-start}``, the code cells, then
``{solution-end}``. sphinx-exercise's ``hide_solutions`` drops a ``{solution}`` directive, but
of a gated solution it drops only the start marker: the cells between stay visible, and the end
marker is left for a writer that does not know it. With ``hide_solutions`` on, this extension
keeps the start marker and removes everything from it to its end marker (siblings in the
document tree, as sphinx-exercise requires of gated directives).
"""

from sphinx.transforms import SphinxTransform
from sphinx_exercise.directive import SolutionStartDirective
from sphinx_exercise.nodes import solution_end_node, solution_start_node


class HiddenSolutionStart(SolutionStartDirective):
    """``solution-start``, which leaves a marker even when solutions are hidden."""

    def run(self):
        nodes = super().run()     # registers the start for sphinx-exercise's structure check
        return nodes if nodes or not self.config.hide_solutions else [solution_start_node()]


class RemoveHiddenSolutions(SphinxTransform):
    """Remove each hidden gated solution: its start marker, its cells, its end marker."""

    default_priority = 5          # before sphinx-exercise merges gated solutions (10)

    def apply(self):
        if not self.config.hide_solutions:
            return
        for start in list(self.document.findall(solution_start_node)):
            siblings = start.parent.children
            first = siblings.index(start)
            last = next(k for k in range(first, len(siblings))
                        if isinstance(siblings[k], solution_end_node))
            del start.parent.children[first:last + 1]


def setup(app):
    app.setup_extension("sphinx_exercise")
    app.add_directive("solution-start", HiddenSolutionStart, override=True)
    app.add_transform(RemoveHiddenSolutions)
    return {"parallel_read_safe": True}

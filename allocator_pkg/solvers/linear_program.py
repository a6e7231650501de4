"""A linear programme with a fixed sparsity pattern on HiGHS (dual simplex, no presolve), set up
once and kept between solves so that each starts from the last basis (the survey's iterative
LP, section 5.3):

    minimise  c'x  subject to  low <= A x <= up,  column_low <= x <= column_up

Between solves only values change: row bounds (``low`` and ``up``, filled in by the caller),
column bounds, and single coefficients of A (sent only when they differ from the value HiGHS
has).

:func:`solve_linear_programme` solves one programme once, given as inequality rows, equality
rows and column bounds (with HiGHS's presolve: nothing is kept for a next solve)."""

from __future__ import annotations

import highspy
import numpy as np
import scipy.sparse as sp

from .backend import NO_BOUND
from .outcome import Outcome, Solution


class LinearProgram:
    """One HiGHS model; :meth:`setup` gives it its structure and first values."""

    def __init__(self, dual_tolerance: float | None = None, presolve: bool = False) -> None:
        """``dual_tolerance``: HiGHS's dual feasibility tolerance (None: its default);
        ``presolve``: HiGHS's presolve before each solve (off: a warm start keeps its basis)."""
        self._highs = highspy.Highs()
        self._highs.setOptionValue("output_flag", False)
        self._highs.setOptionValue("presolve", "on" if presolve else "off")
        if dual_tolerance is not None:
            self._highs.setOptionValue("dual_feasibility_tolerance", dual_tolerance)

    def setup(self, costs: np.ndarray, column_low: np.ndarray, column_up: np.ndarray, a: sp.csc_matrix,
              low: np.ndarray, up: np.ndarray, time_limit: float, keep_basis: bool = False) -> None:
        """The programme's structure and first values (``time_limit`` [s], 0: none). ``low`` and
        ``up`` become the row bounds the caller fills in before each :meth:`solve`.
        ``keep_basis``: start the next solve from the last solve's basis (a model of the same
        shape with new values)."""
        basis = self._highs.getBasis() if keep_basis else None
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = a.shape[1], a.shape[0]
        lp.col_cost_ = costs
        lp.col_lower_, lp.col_upper_ = column_low, column_up
        lp.row_lower_, lp.row_upper_ = low, up
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.start_ = a.indptr
        lp.a_matrix_.index_ = a.indices
        lp.a_matrix_.value_ = a.data
        self._highs.passModel(lp)
        self._highs.setOptionValue("time_limit", time_limit if time_limit > 0.0 else NO_BOUND)
        if basis is not None and basis.valid:
            self._highs.setBasis(basis)
        self.low, self.up = low, up
        self._rows = np.arange(a.shape[0], dtype=np.int32)
        self._columns = a.shape[1]
        self._coefficients: dict[tuple[int, int], float] = {}

    def column_bounds(self, columns: np.ndarray, low: np.ndarray, up: np.ndarray) -> None:
        """New bounds of the ``columns`` (int32 indices)."""
        self._highs.changeColsBounds(columns.size, columns, low, up)

    def coefficient(self, row: int, column: int, value: float) -> None:
        """A new value of one coefficient of A, sent only when it differs from HiGHS's."""
        key = (row, column)
        if self._coefficients.get(key) != value:
            self._coefficients[key] = value
            self._highs.changeCoeff(row, column, value)

    def solve(self, cold: bool = False) -> Solution:
        """Solve with the row bounds in ``low`` and ``up``; ``x`` holds every column (zeros when
        no optimum was found). ``cold``: from no basis (not the last solve's)."""
        highs = self._highs
        if cold:
            highs.clearSolver()
        highs.changeRowsBounds(self._rows.size, self._rows, self.low, self.up)
        highs.run()
        status = highs.getModelStatus()
        iterations = int(highs.getInfo().simplex_iteration_count)
        if status != highspy.HighsModelStatus.kOptimal:
            return Solution(x=np.zeros(self._columns), status=highs.modelStatusToString(status),
                            iterations=iterations, outcome=Outcome.FAILED)
        return Solution(x=np.asarray(highs.getSolution().col_value), status="solved", iterations=iterations,
                        outcome=Outcome.SOLVED)


def solve_linear_programme(cost: np.ndarray, bounds: list[tuple[float | None, float | None]],
                           a_ub: np.ndarray | None = None, b_ub: np.ndarray | None = None,
                           a_eq: np.ndarray | None = None, b_eq: np.ndarray | None = None) -> Solution:
    """minimise cost'x subject to a_ub x <= b_ub, a_eq x = b_eq and each column's ``bounds``
    (low, up; None: unbounded), solved once. ``outcome`` SOLVED with the optimum in ``x``,
    else FAILED (infeasible, unbounded, or no optimum found) with ``x`` zero."""
    columns = len(cost)
    blocks, low, up = [], [], []
    if a_ub is not None and len(a_ub):
        blocks.append(np.asarray(a_ub, dtype=float).reshape(-1, columns))
        up.append(np.asarray(b_ub, dtype=float))
        low.append(np.full(len(up[-1]), -np.inf))
    if a_eq is not None and len(a_eq):
        blocks.append(np.asarray(a_eq, dtype=float).reshape(-1, columns))
        up.append(np.asarray(b_eq, dtype=float))
        low.append(up[-1])
    a = sp.csc_matrix(np.vstack(blocks)) if blocks else sp.csc_matrix((0, columns))
    column_low = np.array([-np.inf if lo is None else lo for lo, _ in bounds], dtype=float)
    column_up = np.array([np.inf if hi is None else hi for _, hi in bounds], dtype=float)
    programme = LinearProgram(presolve=True)
    programme.setup(np.asarray(cost, dtype=float), column_low, column_up, a,
                    np.concatenate(low) if low else np.zeros(0), np.concatenate(up) if up else np.zeros(0), 0.0)
    return programme.solve()

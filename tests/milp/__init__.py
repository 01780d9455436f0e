def unchecked_options(backend: str):
    """``SolverOptions`` naming a backend its checks refuse (an unknown name), for the
    MILP layer's own handling of one: ``SolverOptions(backend="NOPE")`` is refused when
    made (issue 48, item 16), so only such an object reaches a solve."""
    from sdc_cvx.milp.types import SolverOptions

    options = SolverOptions()
    object.__setattr__(options, "backend", backend)
    return options

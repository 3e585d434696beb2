"""impactlab from Python: the simulator, the sweeps, the analysis and the fit of the impactlab CLI.

    import impactlab
    r = impactlab.simulate(impactlab.Model.from_name("A1H"), omega=18, duration=5)
    r["x"][:3]                      # NumPy arrays under the CLI's column names
    import pandas; pandas.DataFrame(r)

Every function runs the core's own code (the same numbers as the CLI), releases the GIL while it computes,
takes progress=callable(fraction) and stops on Ctrl-C (KeyboardInterrupt). Bad input raises ValueError
(ParamError, DataError, ScanError are subclasses) with the CLI's message. Units are SI.
"""
from ._impactlab import (DataError, Model, ParamError, ScanError, SimulationStalled, basins, bifurcation, continue_,
                         effects, fit, lyapunov, models, orbit, poincare, scan, simulate)
from ._result import Result

__all__ = ["Model", "Result", "models", "effects", "simulate", "poincare", "bifurcation", "orbit", "continue_",
           "lyapunov", "basins", "scan", "fit", "ParamError", "DataError", "ScanError", "SimulationStalled"]

"""The result type of impactlab's functions."""


class Result(dict):
    """The columns of a result (NumPy arrays under the CLI's CSV names: pandas.DataFrame(r) is the CSV), with
    the rest of the result as attributes (r.model, r.steps, ...; r.info lists them)."""

    def __init__(self, columns, extras=None):
        super().__init__(columns)
        object.__setattr__(self, "info", dict(extras or {}))

    def __getattr__(self, name):
        try:
            return self.info[name]
        except KeyError:
            raise AttributeError(f"impactlab.Result has no attribute {name!r} (columns: {', '.join(self)}; "
                                 f"attributes: {', '.join(self.info)})") from None

    def __dir__(self):
        return list(super().__dir__()) + list(self.info)

    def __repr__(self):
        rows = len(next(iter(self.values()))) if self else 0
        return f"impactlab.Result({rows} rows: {', '.join(self)}; attributes: {', '.join(self.info)})"

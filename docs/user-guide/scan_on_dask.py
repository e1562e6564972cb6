"""A parameter scan on a temporary local Dask cluster (run as a script)."""
import numpy as np

import persson_fast as pf


def main():
    ds = pf.scan(pf.SelfAffine,
                 {"hurst": [0.7, 0.8], "h_rms": [1e-7, 1e-6], "q0": 1e4, "q1": 1e9},
                 np.linspace(0.0, 10e6, 11), e_star=1e9,
                 client="local")          # one single-threaded worker process per core
    print(ds.area.sel(pressure=10e6).values)


# worker processes are spawned and import this file: without the guard each of them would
# start a cluster of its own
if __name__ == "__main__":
    main()

"""For maintainers: `python -m pyrt.acceleration` prints the fingerprints of the functions
the fast paths repeat as they are now, to copy into the tables of fingerprints.py once
tests/test_acceleration.py shows that the fast paths still give the same answers."""
from pyrt.acceleration.fingerprints import mirrored_functions


def main():
    # Loading the integrators registers their Phong integrator, whose functions count too
    import PyRT_Integrators  # noqa: F401  (registers its PhongIntegrator)
    for name, _, now in mirrored_functions():
        print(f"{name}: {now}")


if __name__ == "__main__":
    main()

# Run by the test regression_python_missing when CMake found no Python 3 with numpy and h5py.
message(FATAL_ERROR
  "The regression tests need a Python 3 with numpy and h5py, and CMake found none.\n"
  "Install them (Debian): apt-get install python3-numpy python3-h5py\n"
  "then re-run cmake (or point it at an interpreter: -DCONTACT2D_PYTHON=/path/to/python3).")

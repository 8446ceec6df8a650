// Module grid comes before module fluid: this include must not compile (lib/CMakeLists.txt).
#include "rbfib/grid/mac.hpp"
#include "rbfib/fluid/navier_stokes.hpp"

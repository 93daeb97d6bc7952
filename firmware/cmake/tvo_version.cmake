# The version of tvo-flat, written once. The top-level project(), firmware/'s own project() when it is
# built on its own (cross builds, the package's standalone builds), the installed package's version
# file (tvoConfigVersion.cmake), tvo.pc and the generated header tvo/version.h all take it from here.
set(tvo_version 1.0.0)

# The fuzz harnesses (tests/fuzz/fuzz_<name>.c), listed once for their build and their CTests.
set(tvo_fuzz_harnesses frame node session controller auth fleet)

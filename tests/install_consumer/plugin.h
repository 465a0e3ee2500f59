#ifndef TRIGRAV_CONSUMER_PLUGIN_H_
#define TRIGRAV_CONSUMER_PLUGIN_H_

#include <cstdint>

// InitializeAndRefine on a noisy synthetic scene drawn with `seed`; its refined rotation error in
// degrees, or 180 if the call failed. Built into the consumer's own shared library.
double RefinedRotationErrorDeg(std::uint64_t seed);

#endif  // TRIGRAV_CONSUMER_PLUGIN_H_

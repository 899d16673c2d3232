// The photon-beam table's cache key: every parameter of the table and the code that made it.
#include "dermis/render/subsurface/profile_from_params.h"

#include <gtest/gtest.h>

#include <string>

#include "dermis/source_hashes.h"

namespace dermis {
namespace {

TEST(PhotonBeamTableKey, NamesTheParametersAndTheCode) {
  const std::string key = photon_beam_table_key(0.25f, 1.33f);
  for (const char* part : {source_hash::kPhotonBeamTable, "g0.25", "eta1.33"})
    EXPECT_NE(key.find(part), std::string::npos) << part << " in " << key;
  EXPECT_NE(photon_beam_table_key(0.25f, 1.4f), key);
  EXPECT_NE(photon_beam_table_key(0.0f, 1.33f), key);
}

}  // namespace
}  // namespace dermis

// The controller addresses a client accepts (address.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hapticctrl/client/connection.hpp"

namespace hapticctrl::client {
namespace {

TEST(Address, TheSchemeAndEitherSeparatorAreAccepted) {
  EXPECT_EQ(Address::parse("udpxdr://10.0.0.2:6000").host, "10.0.0.2");
  EXPECT_EQ(Address::parse("udpxdr://10.0.0.2:6000").port, 6000);
  EXPECT_EQ(Address::parse("lab-pc#7000").host, "lab-pc");
  EXPECT_EQ(Address::parse("lab-pc#7000").port, 7000);
  EXPECT_EQ(Address::parse("lab-pc").port, 5125) << "the protocol's port by default";
}

TEST(Address, ABadPortOrNoHostIsRefusedWithTheText) {
  for (const char* bad : {"udpxdr://host:99999", "host:0", "host:12x", "host:", ":5125", ""}) {
    try {
      (void)Address::parse(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const ClientError& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
      EXPECT_THAT(e.what(), testing::HasSubstr("bad controller address '" + std::string(bad) + "'"))
          << e.what();
    }
  }
}

}  // namespace
}  // namespace hapticctrl::client

// The names of the POD inner product (to_string beside the builder, offline_builder.cpp).
#include <array>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/offline/offline_builder.hpp"

namespace contactrb::offline {

InnerProduct inner_product_from_string(const std::string& name) {
  return enum_from_string(name, "inner product", std::array{InnerProduct::Energy, InnerProduct::H1});
}

}  // namespace contactrb::offline

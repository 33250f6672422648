#pragma once
// Private to reconstruction/meshing: the element limit of adaptive refinement, checked before a
// pass allocates its children (each pass can multiply a mesh by up to 8 or 27).

#include <stdexcept>
#include <string>

namespace interlin::detail {

// std::length_error when max_elements > 0 and the pass would make more than max_elements.
inline void check_element_count(long elements, long max_elements, const char* who) {
  if (max_elements > 0 && elements > max_elements)
    throw std::length_error(std::string(who) + ": the refinement would make " +
                            std::to_string(elements) + " elements, more than the limit of " +
                            std::to_string(max_elements));
}

} // namespace interlin::detail

// Link stand-ins for skaarj1989/FrameGraph's Graphviz writer, whose source needs <format> (GCC
// 12's library has none). Only FrameGraph's operator<< (a debug dump the benchmark never calls)
// refers to it, so these are never run; they abort if they are.
#include <cstdlib>

#include "fg/GraphvizWriter.hpp"

namespace graphviz {

Graph::Graph(Style style_) : style{style_} {}
void Writer::operator()(const PassNode&, const std::vector<ResourceNode>&) { std::abort(); }
void Writer::operator()(const ResourceNode&, const ResourceEntry&, const std::vector<PassNode>&) { std::abort(); }
void Writer::flush(std::ostream&) const { std::abort(); }

}  // namespace graphviz

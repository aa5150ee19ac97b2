#pragma once
// Sends what loom logs while a case runs to that case: errors from anywhere and warnings from
// the backends (GL debug output, Vulkan validation) are the case's problems; the importer's
// warnings are already in Scene::warnings and are dropped here. Outside a case (no route set),
// messages go to the sink that was installed before.

#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "loom/rhi/log.hpp"

namespace loom::compare {

class LogRouter {
public:
    /// Installs itself as loom's log sink; the destructor puts the previous sink back.
    LogRouter();
    ~LogRouter();
    LogRouter(const LogRouter&) = delete;
    LogRouter& operator=(const LogRouter&) = delete;

    /// Where the next messages go as "[level] source: message"; null: to the previous sink.
    void route(std::vector<std::string>* messages);

private:
    void receive(LogLevel level, std::string_view source, std::string_view message);

    LogSink previous_;
    // Drivers may log from their own threads.
    std::mutex mutex_;
    std::vector<std::string>* messages_ = nullptr;
};

}  // namespace loom::compare

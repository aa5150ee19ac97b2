#include "loom/rhi/result.hpp"

namespace loom {

std::string_view error_code_name(ErrorCode code) {
    switch (code) {
        case ErrorCode::InvalidArgument: return "InvalidArgument";
        case ErrorCode::InvalidHandle: return "InvalidHandle";
        case ErrorCode::InvalidState: return "InvalidState";
        case ErrorCode::Unsupported: return "Unsupported";
        case ErrorCode::OutOfMemory: return "OutOfMemory";
        case ErrorCode::ShaderCompile: return "ShaderCompile";
        case ErrorCode::ShaderLink: return "ShaderLink";
        case ErrorCode::Io: return "Io";
        case ErrorCode::Parse: return "Parse";
        case ErrorCode::Graph: return "Graph";
        case ErrorCode::Join: return "Join";
        case ErrorCode::Backend: return "Backend";
        case ErrorCode::DeviceLost: return "DeviceLost";
    }
    return "Unknown";
}

std::string Error::to_string() const {
    std::string out(error_code_name(code));
    out += ": ";
    out += message;
    return out;
}

}  // namespace loom

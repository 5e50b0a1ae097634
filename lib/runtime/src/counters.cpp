#include "ugv/runtime/counters.hpp"

namespace ugv::runtime {

std::atomic<int64_t>& Counters::operator[](const std::string& name)
{
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& item : items_)
        if (item.first == name) return item.second;
    items_.emplace_back(std::piecewise_construct, std::forward_as_tuple(name), std::forward_as_tuple(0));
    return items_.back().second;
}

int64_t Counters::get(const std::string& name) const
{
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& item : items_)
        if (item.first == name) return item.second.load();
    return 0;
}

std::vector<std::pair<std::string, int64_t>> Counters::snapshot() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::pair<std::string, int64_t>> out;
    out.reserve(items_.size());
    for (const auto& item : items_) out.emplace_back(item.first, item.second.load());
    return out;
}

}  // namespace ugv::runtime

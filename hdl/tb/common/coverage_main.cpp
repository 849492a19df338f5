// coverage_main.cpp: the C++ main of a coverage-instrumented testbench build
// (scripts/sim.sh with COVERAGE=1). Verilator 5.006's --binary main never
// writes the coverage counts, so this one runs the same loop (timing
// testbench: advance to the next pending event until $finish) and then
// writes them to the file named by +coverage_file=<path>.
#include <memory>
#include <string>

#include "Vtb.h"
#include "verilated.h"
#include "verilated_cov.h"

int main(int argc, char** argv) {
    const std::unique_ptr<VerilatedContext> contextp{new VerilatedContext};
    contextp->commandArgs(argc, argv);
    const std::unique_ptr<Vtb> topp{new Vtb{contextp.get(), ""}};
    while (!contextp->gotFinish()) {
        topp->eval();
        if (!topp->eventsPending()) break;
        contextp->time(topp->nextTimeSlot());
    }
    if (!contextp->gotFinish()) {
        VL_PRINTF("coverage_main: no more events before $finish\n");
        return 1;
    }
    topp->final();
    const std::string arg = contextp->commandArgsPlusMatch("coverage_file=");
    const std::string prefix = "+coverage_file=";
    const std::string file = arg.size() > prefix.size() ? arg.substr(prefix.size()) : "coverage.dat";
    contextp->coveragep()->write(file.c_str());
    return 0;
}

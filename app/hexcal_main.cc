// hexcal: the headless command-line tool. See docs/cli.md.
#include "app/commands/command_table.h"

int main(int argc, char** argv) { return hexcal::cli::RunHexcal(argc, argv); }

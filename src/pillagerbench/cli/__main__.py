from pillagerbench.cli.commands import main

raise SystemExit(main())

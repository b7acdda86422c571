# fish completion for rscene-from-xml
complete -c rscene-from-xml -s h -l help -d 'Print help and exit'
complete -c rscene-from-xml -l version -d 'Print version and exit'
complete -c rscene-from-xml -s o -l output -r -F -d 'Write the scene to FILE atomically'
complete -c rscene-from-xml -l param -x -d 'Set the template parameter @@NAME to VALUE (NAME=VALUE)'
complete -c rscene-from-xml -l absolute-paths -d 'Write asset paths absolute instead of relative to the output'
complete -c rscene-from-xml -s q -l quiet -d 'Print errors only, no warnings'
complete -c rscene-from-xml -l stdin-filename -r -F -d 'Name standard input in messages and for [THIS_DIR]'
complete -c rscene-from-xml -k -x -a '(__fish_complete_suffix .xml)'
